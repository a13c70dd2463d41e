#include "specula/report/report.h"

#include <chrono>
#include <fmt/format.h>
#include <string>
#include <thread>

#include "context.h"
#include "sections.h"
#include "specula/exceptions.h"
#include "specula/io/files.h"

namespace specula::report {
namespace {

constexpr const char* kStyle = R"(
body { font: 16px/1.5 system-ui, sans-serif; max-width: 70rem; margin: 2rem auto; padding: 0 1rem; color: #1b1b1b; }
h1 { font-size: 1.8rem; margin-bottom: 0; } h2 { margin-top: 2.5rem; border-bottom: 1px solid #ccc; }
h3 { margin-top: 1.8rem; }
.lede { color: #555; margin-top: .25rem; }
nav ol { columns: 2; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; margin: 1rem 0; }
th, td { padding: .2rem .7rem; text-align: right; border-bottom: 1px solid #eee; vertical-align: top; }
th { background: #f4f4f4; } td.ok { color: #11691d; } td.bad { color: #a4161a; }
table.claims td, table.claims th, table.text td { text-align: left; }
table.models td:first-child { text-align: left; white-space: nowrap; } table.verdicts td:last-child { text-align: left; min-width: 17rem; }
code, pre { font: 13px/1.4 ui-monospace, monospace; background: #f6f6f6; }
pre { padding: .6rem; overflow-x: auto; }
figure { margin: 1.5rem 0; } figure svg, figure img { max-width: 100%; height: auto; }
figcaption { color: #333; font-size: .92rem; max-width: 60rem; } .cmd, .files { color: #555; }
.cols { columns: 2; column-gap: 2rem; }
.grid { display: flex; flex-wrap: wrap; gap: 1rem; } .grid figure { margin: 0; flex: 1 1 26rem; }
@media print { body { max-width: none; } details { display: block; } figure { break-inside: avoid; } }
)";

std::string page(const std::vector<Section>& sections, const Context& context, double seconds) {
  std::string toc, body;
  for (const Section& s : sections) {
    toc += fmt::format("<li><a href=\"#{}\">{}</a></li>", s.id, s.title);
    body += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n", s.id, s.title, s.html);
  }
  return fmt::format(R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>specula report</title>
<meta name="viewport" content="width=device-width, initial-scale=1"><style>{}</style></head>
<body>
<h1>specula report</h1>
<p class="lede">O. Romanyuk et al., “The Development of Physically Correct Reflectance Model Based on Logarithm
Function” (ACIT 2023), reproduced end to end from specula's own computations — then what the paper could not
see.{}</p>
<nav><ol>{}</ol></nav>
{}<footer><p class="lede">Written by <code>specula report{}</code> in {:.1f} s on {} hardware threads; {} files beside
this page. Every number is computed by specula at report time; the paper's own numbers are quoted as printed.</p></footer>
</body></html>
)",
                     kStyle, context.quick() ? " <strong>Quick mode: coarse sweeps and short searches.</strong>" : "",
                     toc, body, context.quick() ? " --quick" : "", seconds, std::thread::hardware_concurrency(),
                     context.files().size());
}

}  // namespace

void write_report(const Options& requested) {
  io::StagedDirectory out(requested.out_dir, {"report", "fig5-normalization.csv"});
  Options options = requested;
  options.out_dir = out.path();
  const auto start = std::chrono::steady_clock::now();
  Context context(options);
  std::vector<Section> sections;
  sections.push_back(lobes_section(context));
  sections.push_back(normalization_section(context));
  sections.push_back(shader_section(context));
  sections.push_back(energy_section(context));
  sections.push_back(compensation_section(context));
  sections.push_back(fitted_norms_section(context));
  sections.push_back(cost_section(context));
  sections.push_back(designed_section(context));
  sections.push_back(engine_terms_section(context));
  sections.push_back(differences_section(context));
  sections.insert(sections.begin(), claims_section(context));
  context.progress("index.html");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  context.write("index.html", page(sections, context, seconds));
  out.commit();
}

}  // namespace specula::report
