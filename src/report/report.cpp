#include "specula/report/report.h"

#include <cmath>
#include <fmt/format.h>
#include <string>

#include "specula/error.h"
#include "specula/io/table.h"
#include "specula/io/values.h"
#include "specula/models/model.h"
#include "specula/normalize/closed_form.h"

namespace specula::report {
namespace {

// The paper's Fig. 5 file as printed (n = 1…7; the other 43 rows are not legible).
constexpr double kPaperFig5[] = {0.483, 0.665, 0.855, 1.048, 1.243, 1.438, 1.634};

constexpr const char* kStyle = R"(
body { font: 16px/1.5 system-ui, sans-serif; max-width: 60rem; margin: 2rem auto; padding: 0 1rem;
       color: #1b1b1b; }
h1 { font-size: 1.8rem; margin-bottom: 0; } h2 { margin-top: 2.5rem; border-bottom: 1px solid #ccc; }
.lede { color: #555; margin-top: .25rem; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; margin: 1rem 0; }
th, td { padding: .2rem .8rem; text-align: right; border-bottom: 1px solid #eee; }
th { background: #f4f4f4; } td.ok { color: #11691d; } td.bad { color: #a4161a; }
code, pre { font: 14px/1.4 ui-monospace, monospace; background: #f6f6f6; }
pre { padding: .6rem; overflow-x: auto; }
.cols { columns: 2; column-gap: 2rem; } @media print { .cols { columns: 2; } }
)";

io::Table fig5_table() {
  io::Table table{{"n", "coef_exact", "coef_exact_3dp", "coef_paper_fit", "delta_paper_fit"}, {}, {}};
  for (const double n : io::paper50()) {
    const double exact = normalize::log_rv(n);
    const double fit = make_model("log-paper", {{"n", n}}).coef();
    table.rows.push_back({n, exact, std::round(exact * 1000) / 1000, fit, (fit - exact) / exact});
  }
  return table;
}

std::string paper_check_rows() {
  std::string rows;
  for (int i = 0; i < 7; ++i) {
    const double exact = normalize::log_rv(i + 1);
    const bool same = std::round(exact * 1000) / 1000 == kPaperFig5[i];
    rows += fmt::format("<tr><td>{}</td><td>{:.3f}</td><td>{:.3f}</td><td>{:.17g}</td><td class='{}'>{}</td></tr>\n",
                        i + 1, kPaperFig5[i], exact, exact, same ? "ok" : "bad", same ? "same" : "differs");
  }
  return rows;
}

std::string fig5_rows(const io::Table& table) {
  std::string rows;
  for (const auto& r : table.rows)
    rows += fmt::format("<tr><td>{}</td><td>{:.3f}</td><td>{:.15g}</td><td>{:.6f}</td><td>{:+.3e}</td></tr>\n",
                        r[0], r[1], r[1], r[3], r[4]);
  return rows;
}

std::string html(const io::Table& fig5) {
  return fmt::format(R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>specula report</title>
<meta name="viewport" content="width=device-width, initial-scale=1"><style>{}</style></head>
<body>
<h1>specula report</h1>
<p class="lede">Romanyuk et al., “The Development of Physically Correct Reflectance Model Based on
Logarithm Function” (ACIT 2023), reproduced from specula's own computations.</p>

<h2 id="fig5">Fig. 5: the normalization table</h2>
<p>coef(n) = 1/(2π Int(n)) makes the log lobe F<sub>log</sub> reflect all the energy it receives at
normal incidence. specula computes it in closed form with the exponential integral
(MATH.md §4, ≤ 1e-13 relative for n ∈ [1e-3, 1e9]). The paper printed the first seven rows of its
50-row file:</p>
<table><thead><tr><th>n</th><th>paper</th><th>specula, 3 decimals</th><th>specula, exact</th><th>verdict</th></tr></thead>
<tbody>
{}</tbody></table>
<p>The 50 values of n (the paper does not print them past 7; specula uses n₀ = 1,
nᵢ = max(nᵢ₋₁ + 1, round(1000<sup>i/49</sup>))), the exact coefficient, and the paper's fitted formula
k = 0.197(n + 1.24) + 0.068/(0.64 + n) with its relative deviation Δ = k<sub>fit</sub>·2π·Int − 1
(the paper's Fig. 9). Data: <a href="fig5-normalization.csv">fig5-normalization.csv</a>; regenerate with
<code>specula normalize --model log --n paper50 --compare log-paper</code>.</p>
<div class="cols"><table><thead><tr><th>n</th><th>coef (3 dp)</th><th>coef, exact</th><th>paper's fit</th><th>Δ</th></tr></thead>
<tbody>
{}</tbody></table></div>
<p>At n = 1000 the paper's fit under-normalizes by {:.3f} %.</p>
</body></html>
)",
                     kStyle, paper_check_rows(), fig5_rows(fig5), -100 * fig5.rows.back()[4]);
}

}  // namespace

void write_report(const Options& options) {
  std::error_code ec;
  std::filesystem::create_directories(options.out_dir, ec);
  if (ec)
    throw InvalidArgument(fmt::format("cannot create '{}': {}", options.out_dir.string(), ec.message()));
  options.progress("Fig. 5: the normalization table");
  const io::Table fig5 = fig5_table();
  io::write_file_atomically(options.out_dir / "fig5-normalization.csv", io::to_csv(fig5));
  options.progress("index.html");
  io::write_file_atomically(options.out_dir / "index.html", html(fig5));
}

}  // namespace specula::report
