#include "specula/report/design_page.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "context.h"
#include "specula/catalogue/catalogue.h"
#include "specula/glsl/glsl.h"
#include "specula/io/files.h"
#include "specula/render/image_io.h"

namespace specula::report {

namespace {

constexpr const char* kStyle = R"(
body { font: 16px/1.5 system-ui, sans-serif; max-width: 70rem; margin: 2rem auto; padding: 0 1rem; color: #1b1b1b; }
h1 { font-size: 1.8rem; margin-bottom: 0; } h2 { margin-top: 2.5rem; border-bottom: 1px solid #ccc; }
.lede { color: #555; margin-top: .25rem; }
table { border-collapse: collapse; font-variant-numeric: tabular-nums; margin: 1rem 0; }
th, td { padding: .2rem .7rem; text-align: right; border-bottom: 1px solid #eee; vertical-align: top; }
th { background: #f4f4f4; } table.models td:first-child, table.models td:last-child { text-align: left; }
code, pre { font: 13px/1.4 ui-monospace, monospace; background: #f6f6f6; }
pre { padding: .6rem; overflow-x: auto; }
figure { margin: 1.5rem 0; } figure svg { max-width: 100%; height: auto; }
)";

bool timed(const design::Result& r) {
  return !r.front.empty() && std::ranges::all_of(r.front, [](const design::Lobe& l) { return std::isfinite(l.ns_per_eval); });
}

double cost_of(const design::Lobe& l, bool measured) { return measured ? l.ns_per_eval : l.model_cost; }

// F and the target as functions of c at parameter value p.
std::function<double(double)> curve(const Model& m) {
  return [lobe = m.lobe()](double c) { return lobes::eval(lobe, c); };
}

std::vector<double> curve_params(const design::Settings& s) { return {s.lo, design::middle(s.lo, s.hi), s.hi}; }

std::string member_glsl(const design::Result& r, const design::Lobe& l) {
  return glsl::model_glsl(design::lobe_at(l, r.settings)(design::timing_param(r.settings)));
}

// A function member as a GLSL function of the per-pixel variables and the range parameter.
std::string function_glsl(const design::Result& r, const design::Lobe& l) {
  std::string arguments;
  for (const auto& name : design::formula_variables(r.settings))
    arguments += (arguments.empty() ? "float " : ", float ") + name;
  return fmt::format("float specula_term({}) {{\n  return {};\n}}\n", arguments,
                     expr::to_glsl(design::function_expression(r.settings, l.formula)));
}

// |F − target| of a function member against its first variable at parameter value p, the largest
// over a grid of the other variables (each over (0, 1]).
std::vector<double> function_error_curve(const design::Result& r, const design::Lobe& member, double p,
                                         const std::vector<double>& first) {
  const design::Settings& s = r.settings;
  const expr::Expression f = design::function_expression(s, member.formula);
  const auto t = design::target_function(s);
  constexpr int kOthers = 32;
  const std::size_t others = s.variables.size() - 1;
  std::size_t combinations = 1;
  for (std::size_t i = 0; i < others; ++i) combinations *= kOthers;
  std::vector<double> out;
  std::vector<double> point(design::formula_variables(s).size());
  if (!s.param.empty()) point.back() = p;
  for (double x : first) {
    point[0] = x;
    double worst = 0;
    for (std::size_t j = 0; j < combinations; ++j) {
      for (std::size_t i = 0, rest = j; i < others; ++i, rest /= kOthers)
        point[i + 1] = static_cast<double>(rest % kOthers + 1) / kOthers;
      const double e = std::abs(expr::evaluate(f, point) - t(point));
      worst = std::isnan(e) ? e : std::max(worst, e);
      if (std::isnan(worst)) break;
    }
    out.push_back(worst);
  }
  return out;
}

}  // namespace

namespace {

// The front chart, or what stands for it when no lobe was finished or none can be drawn on its
// log axes (a cost or an error of 0: the lobe F = c costs 0 in the cost model).
std::string front_figure(const design::Result& r) {
  if (r.front.empty()) return "<p>No lobe was finished: nothing to draw (a longer <code>--time</code> screens shapes).</p>";
  const Chart chart = design_front_chart(r);
  if (!has_points(chart)) return "<p>No member has a cost and an error above 0: nothing to draw on log axes.</p>";
  return to_svg(chart);
}

// A member's error chart, or a note where it has no finite point.
std::string error_figure(const design::Result& r, const design::Lobe& member) {
  const Chart chart = design_error_chart(r, member);
  return has_points(chart) ? to_svg(chart) : "<p>|F − target| is nowhere finite: nothing to draw.</p>";
}

}  // namespace

Chart design_front_chart(const design::Result& r) {
  const bool measured = timed(r);
  Chart chart;
  chart.title = fmt::format("Designed lobes against {} over {} ∈ [{:g}, {:g}]", r.settings.target, r.settings.param,
                            r.settings.lo, r.settings.hi);
  chart.x = {measured ? "cost (ns per value, float, one core)" : "cost (the cost model's units)", Scale::log, {}, {}};
  chart.y = {fmt::format("largest |F − {}| over the domain", r.settings.target), Scale::log, {}, {}};
  Series front{"designed front", model_colour("design"), {}, {}, Stroke::solid, true, {}};
  for (const auto& l : r.front) {
    const double x = cost_of(l, measured);
    if (!front.x.empty()) {  // the staircase: across at the previous error, then down
      front.x.push_back(x);
      front.y.push_back(front.y.back());
    }
    front.x.push_back(x);
    front.y.push_back(l.max_abs);
  }
  chart.series.push_back(front);
  if (measured)
    for (const auto& l : r.references)
      if (l.max_abs > 0)
        chart.series.push_back({l.id, model_colour(l.id), {l.ns_per_eval}, {l.max_abs}, Stroke::none, true, {l.id}});
  chart.legend = Legend::top_right;
  return chart;
}

Chart design_gpu_chart(const design::Result& r) {
  Chart chart;
  chart.title = fmt::format("On the GPU: designed members against {}", r.settings.target);
  // A time at or below the baseline's (0: within the timing's noise) is drawn at 0.1 ps.
  static constexpr double kFloor = 0.1;
  const auto x_of = [](const design::Lobe& l) { return std::max(l.gpu_ps_per_eval, kFloor); };
  chart.x = {"GPU cost (ps per evaluation, float; 0.1: within the timing's noise)", Scale::log, {}, {}};
  chart.y = {fmt::format("largest |F − {}| over the domain", r.settings.target), Scale::log, {}, {}};
  Series front{"front on the GPU", model_colour("design"), {}, {}, Stroke::solid, true, {}};
  for (const auto& l : r.front) {
    if (!l.gpu_front || !std::isfinite(l.gpu_ps_per_eval)) continue;
    if (!front.x.empty()) {  // the staircase, as the CPU's
      front.x.push_back(x_of(l));
      front.y.push_back(front.y.back());
    }
    front.x.push_back(x_of(l));
    front.y.push_back(l.max_abs);
  }
  chart.series.push_back(front);
  for (const auto& l : r.references)
    if (l.max_abs > 0 && std::isfinite(l.gpu_ps_per_eval))
      chart.series.push_back({l.id, model_colour(l.id), {x_of(l)}, {l.max_abs}, Stroke::none, true, {l.id}});
  chart.legend = Legend::top_right;
  return chart;
}

Chart design_error_chart(const design::Result& r, const design::Lobe& member) {
  const design::Settings& s = r.settings;
  const bool function = design::is_function_target(s.target);
  const std::string& first = s.variables.front();
  Chart chart;
  chart.title = fmt::format("{}: |F − {}| against {}{}", member.id, s.target, first,
                            s.variables.size() > 1 ? " (the largest over the other variables)" : "");
  chart.x = {first, Scale::linear, 0.0, 1.0};
  chart.y = {"|F − target|", Scale::linear, 0.0, {}};
  const char* colours[] = {"#0072B2", "#D55E00", "#009E73"};
  std::size_t k = 0;
  std::vector<double> xs;
  for (int i = function ? 1 : 0; i <= 400; ++i)  // a lobe's c denser near 1, where narrow lobes live; a function's even
    xs.push_back(function ? i / 400.0 : std::pow(i / 400.0, 0.25));
  for (double p : s.param.empty() ? std::vector<double>{s.lo} : curve_params(s)) {
    Series series{s.param.empty() ? std::string("|F − target|") : fmt::format("{} = {:g}", s.param, p), colours[k++ % 3], xs,
                  {}, Stroke::solid, false, {}};
    if (function) {
      series.y = function_error_curve(r, member, p, xs);
    } else {
      const auto f = curve(design::lobe_at(member, s)(p));
      const auto t = curve(design::target_at(s, p));
      for (double c : xs) series.y.push_back(std::abs(f(c) - t(c)));
    }
    chart.series.push_back(std::move(series));
  }
  chart.legend = Legend::top_left;
  chart.width = 520;
  chart.height = 320;
  return chart;
}

namespace {

std::string function_member(const design::Result& r, const design::Lobe& l) {
  const design::Settings& s = r.settings;
  const std::string where = s.param.empty() ? std::string()
                                            : fmt::format(", {} = {}", xml_escape(s.param), show(l.argmax_param, 6));
  return fmt::format("<h2 id=\"{0}\">{0}</h2>\n<p><code>F = {1}</code></p>\n<p>Largest |F − {2}| = {3} at {4} = {5}{6}.</p>\n"
                     "<figure>{7}</figure>\n<details><summary>GLSL</summary><pre>{8}</pre></details>\n",
                     xml_escape(l.id), xml_escape(l.formula), xml_escape(s.target), show(l.max_abs, 6),
                     xml_escape(s.variables.front()), show(l.argmax_c, 6), where, error_figure(r, l),
                     xml_escape(function_glsl(r, l)));
}

}  // namespace

std::string design_page(const design::Result& r) {
  const design::Settings& s = r.settings;
  std::vector<std::vector<std::string>> rows;
  const auto row = [&](const design::Lobe& l) {
    rows.push_back({xml_escape(l.id), l.reference ? "reference" : "member", show(l.max_abs), show(l.max_rel),
                    std::isfinite(l.ns_per_eval) ? show(l.ns_per_eval, 3) : "–", l.ops > 0 ? std::to_string(l.ops) : "–",
                    std::isfinite(l.spirv_instructions) ? show(l.spirv_instructions, 3) : "–",
                    l.reference ? "–" : xml_escape(l.check), "<code>" + xml_escape(l.formula) + "</code>"});
  };
  for (const auto& l : r.front) row(l);
  for (const auto& l : r.references) row(l);
  std::string members;
  for (const auto& l : r.front) {
    if (design::is_function_target(s.target)) {
      members += function_member(r, l);
      continue;
    }
    members += fmt::format(
        "<h2 id=\"{0}\">{0}</h2>\n<p><code>F = {1}</code></p>\n<p>Largest |F − {2}| = {3} at c = {4}, {5} = {6}; "
        "largest relative error where {2} ≥ {7}: {8}. Normalized: k({5} = {9}) = {10} {15} (the model "
        "<code>{0}-normalized</code>); <code>specula check</code> at {5} = {11}: {12}.</p>\n<figure>{13}</figure>\n"
        "<details><summary>GLSL</summary><pre>{14}</pre></details>\n",
        xml_escape(l.id), xml_escape(l.formula), xml_escape(s.target), show(l.max_abs, 6), show(l.argmax_c, 6),
        xml_escape(s.param), show(l.argmax_param, 6), s.zone, show(l.max_rel, 6), show(design::timing_param(s), 4),
        show(l.k, 6), xml_escape(fmt::format("{:g}", fmt::join(design::check_params(s), ", "))),
        xml_escape(l.check), error_figure(r, l), xml_escape(member_glsl(r, l)),
        l.k_formula.empty() ? std::string("by quadrature")
                            : "in closed form, k(" + xml_escape(s.param) + ") = <code>" + xml_escape(l.k_formula) + "</code>");
  }
  return fmt::format(R"(<!doctype html>
<html lang="en"><head><meta charset="utf-8"><title>specula design: {0}</title>
<meta name="viewport" content="width=device-width, initial-scale=1"><style>{1}</style></head>
<body>
<h1>Designed lobes against {0}</h1>
<p class="lede">{2} over {3} ∈ [{4:g}, {5:g}], objective {6}: {7} of {8} shapes screened in {9:.1f} s{10}. {11}; {15}.</p>
<figure>{12}</figure>
{16}
{13}
{14}
<footer><p class="lede">Written by <code>specula design</code>; the files beside this page: front.csv, models.toml,
design.json, front.svg, front.png. Load the lobes in any command with <code>--models models.toml</code>.</p></footer>
</body></html>
)",
                     xml_escape(s.target), kStyle, xml_escape(s.target), xml_escape(s.param), s.lo, s.hi,
                     to_string(s.objective), r.forms_screened, r.forms_total, r.seconds,
                     r.cancelled ? " (stopped early)" : "", xml_escape(r.cost_note), front_figure(r),
                     html_table({"id", "kind", "max |F − target|", "max rel.", "ns/value", "ops", "SPIR-V", "check",
                                 "formula"},
                                rows, "models"),
                     members, xml_escape(r.spirv_note),
                     has_points(design_gpu_chart(r))
                         ? fmt::format("<figure>{}</figure>\n<p class=\"lede\">{}.</p>", to_svg(design_gpu_chart(r)), xml_escape(r.gpu_note))
                         : std::string());
}

void write_design_pictures(const design::Result& r, const std::filesystem::path& dir) {
  const Chart front = design_front_chart(r);
  if (has_points(front)) {  // else no lobe finished (a --time spent before any), or none drawable: no front to draw
    io::write_file_atomically(dir / "front.svg", to_svg(front));
    render::write_png(dir / "front.png", to_image(front), {{"Software", "specula design"}});
  }
  if (const Chart gpu = design_gpu_chart(r); has_points(gpu)) io::write_file_atomically(dir / "front-gpu.svg", to_svg(gpu));
  io::write_file_atomically(dir / "index.html", design_page(r));
}

}  // namespace specula::report
