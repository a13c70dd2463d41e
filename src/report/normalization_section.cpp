// The paper's Figs. 5, 7-8 and 9: the normalization table, its symbolic regression, and how well
// the fitted formula normalizes (Δ(n) = k_fit · 2π Int(n) − 1 = k_fit/coef − 1).
#include <cmath>
#include <fmt/format.h>

#include "sections.h"
#include "specula/expr/expr.h"
#include "specula/fit/fit.h"
#include "specula/io/values.h"
#include "specula/catalogue/catalogue.h"
#include "specula/lobes/closed_form.h"
#include "specula/normalize/normalize.h"
#include "specula/report/plot.h"

namespace specula::report {
namespace {

// The paper's Fig. 5 file as printed (n = 1…7; the other 43 rows are not legible).
constexpr double kPaperFig5[] = {0.483, 0.665, 0.855, 1.048, 1.243, 1.438, 1.634};

// The paper's Fig. 8: TuringBot's Pareto front on the 50-row table (docs/math.md §5).
struct PaperFront {
  int size;
  double rms;
  const char* formula;
};
constexpr PaperFront kTuringBot[] = {
    {1, 62.583411, "58.7142"},
    {3, 0.183519, "0.197639·n"},
    {5, 0.006839, "0.197244·(n + 1.27235)"},
    {9, 0.006503, "(0.197234 − (−1.39266e-08·n))·(n + 1.2752)"},
    {10, 0.001128, "0.197253·((0.224161/n) + 1.2449 + n)"},
    {12, 0.000280, "0.197254·(n + 1.23891) + (0.0681339/(0.641677 + n))"},
    {18, 0.000273, "(a longer formula, not legible)"}};

double round3(double v) { return std::round(v * 1000) / 1000; }

std::string fig5(Context& context) {
  DataTable table{"fig5-normalization", {"n", "coef_exact", "coef_exact_3dp", "coef_paper_fit", "delta_paper_fit"}, {}};
  std::vector<std::vector<std::string>> rows;
  for (const double n : io::paper50()) {
    const double exact = lobes::log_rv(n);
    const double fit = make_model("log-paper", {{"n", n}}).coef();
    table.rows.push_back({n, exact, round3(exact), fit, fit / exact - 1});
    rows.push_back({fmt::format("{:g}", n), fmt::format("{:.3f}", exact), fmt::format("{:.15g}", exact),
                    fmt::format("{:.6f}", fit), show(fit / exact - 1, 3)});
  }
  int matched = 0;
  std::vector<std::vector<std::string>> paper_rows;
  for (int i = 0; i < 7; ++i) {
    const double exact = lobes::log_rv(i + 1);
    const bool same = round3(exact) == kPaperFig5[i];
    matched += same;
    paper_rows.push_back({std::to_string(i + 1), fmt::format("{:.3f}", kPaperFig5[i]), fmt::format("{:.3f}", exact),
                          fmt::format("{:.17g}", exact),
                          fmt::format("<td class=\"{}\">{}</td>", same ? "ok" : "bad", same ? "same" : "differs")});
  }
  context.findings["fig5_matched"] = {static_cast<double>(matched), fmt::format("{}/7", matched)};
  const std::string links = context.save(table);
  return "<h3 id=\"fig5\">Fig. 5: the normalization table</h3>\n"
         "<p>coef(n) = 1/(2π Int(n)) makes F<sub>log</sub> reflect all the energy it receives at normal incidence. "
         "specula computes it in closed form with the exponential integral (docs/math.md §4; ≤ 10<sup>−13</sup> relative "
         "for n ∈ [10<sup>−3</sup>, 10<sup>9</sup>]). The paper printed the first seven rows of its 50-row file:</p>\n" +
         html_table({"n", "paper", "specula, 3 decimals", "specula, exact", "verdict"}, paper_rows) +
         fmt::format("<p>All 50 rows: n<sub>0</sub> = 1, n<sub>i</sub> = max(n<sub>i−1</sub> + 1, round(1000<sup>i/49</sup>)) "
                     "(the paper does not print its n past 7), the exact coefficient, and the paper's formula "
                     "k = 0.197(n + 1.24) + 0.068/(0.64 + n) with Δ = k<sub>fit</sub>·2π·Int − 1. Files: {}. "
                     "Regenerate: <code>specula normalize --model log --n paper50 --compare log-paper</code></p>\n",
                     links) +
         "<details><summary>The 50 rows</summary><div class=\"cols\">" +
         html_table({"n", "coef (3 dp)", "coef, exact", "paper's fit", "Δ"}, rows) + "</div></details>\n";
}

struct Fits {
  fit::Result rounded;  ///< on the 3-decimal table, TuringBot's size weights: the paper's setting
  fit::Result exact;    ///< on the exact coefficients, default weights: how far a formula can go
};

fit::Result run_fit(const Context& context, const std::vector<double>& target, bool turingbot) {
  fit::Data data{{"n"}, {io::paper50()}, target};
  fit::Options options;
  options.operators = fit::parse_operators("+,*,/");
  options.weights = fit::SizeWeights::parse(turingbot ? "turingbot" : "default");
  options.max_size = 25;
  options.time_limit_s = 600;
  options.max_generations = context.quick() ? 6 : 300;
  options.population = context.quick() ? 60 : 200;
  if (context.quick()) {
    options.enumerate_max_size = 7;
    options.enumerate_limit = 1500;
  }
  return fit::search(data, options);
}

std::string front_svg(const Fits& fits) {
  Chart chart{"Fig. 8: Pareto front, RMS error against size", {"formula size (nodes; ÷ counts 2)", Scale::linear, 0, 26},
              {"RMS error", Scale::log, std::nullopt, std::nullopt}, {}};
  Series paper{"TuringBot (the paper)", "#777777", {}, {}, Stroke::dotted, true};
  for (const auto& p : kTuringBot) {
    paper.x.push_back(p.size);
    paper.y.push_back(p.rms);
  }
  Series ours{"specula fit, same table", model_colour("log-paper"), {}, {}, Stroke::solid, true};
  for (const auto& c : fits.rounded.front) {
    ours.x.push_back(c.size);
    ours.y.push_back(c.train_error);
  }
  Series exact{"specula fit, exact coef (÷ counts 1)", model_colour("log-normalized"), {}, {}, Stroke::dashed, true};
  for (const auto& c : fits.exact.front) {
    exact.x.push_back(c.size);
    exact.y.push_back(c.train_error);
  }
  chart.series = {paper, ours, exact};
  return to_svg(chart);
}

std::string shown(const expr::Expression& e) { return xml_escape(expr::to_infix(fit::rounded(e, 6))); }

std::string fig8(Context& context, const Fits& fits) {
  DataTable table{"fig8-pareto-front", {"source", "size", "rms", "formula"}, {}};
  for (const auto& p : kTuringBot) table.rows.push_back({std::string("turingbot"), double(p.size), p.rms, std::string(p.formula)});
  for (const auto& c : fits.rounded.front)
    table.rows.push_back({std::string("specula-rounded"), double(c.size), c.train_error, expr::to_infix(c.formula)});
  for (const auto& c : fits.exact.front)
    table.rows.push_back({std::string("specula-exact"), double(c.size), c.train_error, expr::to_infix(c.formula)});
  const std::string links = context.save(table);

  std::vector<std::vector<std::string>> rows;
  for (const auto& p : kTuringBot) rows.push_back({"TuringBot", std::to_string(p.size), show(p.rms, 4), xml_escape(p.formula)});
  double best12 = INFINITY;
  std::string best12_formula;
  for (const auto& c : fits.rounded.front) {
    rows.push_back({"specula", std::to_string(c.size), show(c.train_error, 4), shown(c.formula)});
    if (c.size <= 12 && c.train_error < best12) {
      best12 = c.train_error;
      best12_formula = expr::to_infix(fit::rounded(c.formula, 6));
    }
  }
  context.findings["fit_rms_size12"] = {best12, show(best12, 4)};
  context.findings["fit_formula_size12"] = {best12, best12_formula};
  const auto& r = fits.rounded;
  return "<h3 id=\"fig8\">Figs. 7–8: symbolic regression of the table</h3>\n"
         "<p>The paper fitted its 50-row table (coefficients to 3 decimals) with TuringBot, operators + × ÷. "
         "specula's own <code>fit</code> (exhaustive enumeration of small forms, then genetic programming on "
         "islands, every constant fitted by least squares) on the same table with the same size measure: " +
         fmt::format("{} generations, {} formulas fitted in {:.1f} s.</p>\n", r.generations, r.evaluations, r.seconds) +
         context.svg_figure("fig8-pareto-front", front_svg(fits),
                            "The RMS floor ≈ 2.9·10<sup>−4</sup> is the rounding of the data to 3 decimals "
                            "(0.001/√12): below it a formula fits the rounding, not coef(n). On the exact "
                            "coefficients (dashed) the error keeps falling with size.",
                            "specula normalize --model log --n paper50 --round 3 -o fig5.csv && "
                            "specula fit --data fig5.csv --target coef --vars n --ops +,*,/ --size-weights turingbot",
                            links) +
         "<details open><summary>Both fronts</summary>" + html_table({"tool", "size", "RMS", "formula"}, rows) +
         "</details>\n";
}

/// Δ(n) = k(n)/coef(n) − 1 of a formula in n.
std::vector<double> deltas(const std::vector<double>& ns, const std::function<double(double)>& k) {
  std::vector<double> out;
  for (const double n : ns) out.push_back(k(n) / lobes::log_rv(n) - 1);
  return out;
}

std::string fig9(Context& context, const Fits& fits) {
  const std::vector<double> ns = log_spaced(1, 1000, context.quick() ? 40 : 400);
  const auto formula = [](const expr::Expression& e) {
    return [e](double n) { return expr::evaluate(e, std::span<const double>(&n, 1)); };
  };
  const auto& chosen = fits.rounded.front[fits.rounded.chosen];
  const auto& best = fits.exact.front.back();
  struct Curve {
    std::string name, column, colour;
    Stroke stroke;
    std::vector<double> delta;
  };
  std::vector<Curve> curves{
      {"the paper's printed formula", "delta_paper", model_colour("log-paper"), Stroke::solid,
       deltas(ns, [](double n) { return make_model("log-paper", {{"n", n}}).coef(); })},
      {"TuringBot, full precision", "delta_turingbot", "#777777", Stroke::dotted,
       deltas(ns, [](double n) { return 0.197254 * (n + 1.23891) + 0.0681339 / (0.641677 + n); })},
      {fmt::format("specula, size {} (3-decimal table)", chosen.size), "delta_specula_rounded", "#0072b2", Stroke::dashed,
       deltas(ns, formula(chosen.formula))},
      {fmt::format("specula, size {} (exact coef)", best.size), "delta_specula_exact", model_colour("log-normalized"),
       Stroke::solid, deltas(ns, formula(best.formula))},
      {"closed form, checked by quadrature", "delta_closed_form", "#000000", Stroke::dotted,
       deltas(ns, [](double n) {
         return lobes::log_rv(n) * lobes::log_rv(n) /
                normalize::coefficient(lobes::Log<>{n}, Form::rv, normalize::Method::quadrature);
       })}};
  DataTable table{"fig9-delta", {"n"}, {}};
  for (const auto& c : curves) table.columns.push_back(c.column);
  Chart chart{"Fig. 9: normalization error |Δ(n)| of fitted formulas", {"n (specular exponent)", Scale::log, 1, 1000},
              {"|Δ(n)| = |k_fit · 2π Int(n) − 1|", Scale::log, std::nullopt, std::nullopt}, {}};
  for (const auto& c : curves) {
    Series s{c.name, c.colour, ns, {}, c.stroke};
    for (const double d : c.delta) s.y.push_back(std::abs(d));
    chart.series.push_back(std::move(s));
  }
  chart.legend = Legend::bottom_left;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    std::vector<Cell> row{ns[i]};
    for (const auto& c : curves) row.emplace_back(c.delta[i]);
    table.rows.push_back(std::move(row));
  }
  const double paper_1000 = curves[0].delta.back();
  context.findings["paper_delta_1000"] = {paper_1000, show(paper_1000, 3)};
  double worst_exact = 0;
  for (const double d : curves[3].delta) worst_exact = std::max(worst_exact, std::abs(d));
  context.findings["specula_fit_delta"] = {worst_exact, show(worst_exact, 2)};
  double worst_closed = 0;
  for (const double d : curves[4].delta) worst_closed = std::max(worst_closed, std::abs(d));
  return "<h3 id=\"fig9\">Fig. 9: how well the fitted formulas normalize</h3>\n" +
         context.svg_figure(
             "fig9-delta", to_svg(chart),
             fmt::format("Δ(n) = k<sub>fit</sub>(n)·2π·Int(n) − 1, with Int(n) from the exact closed form (docs/math.md §4). The "
                         "paper's printed formula under-normalizes by {} % at n = 1000 (its constants are rounded to 3 "
                         "digits); specula's size-{} formula on the exact coefficients stays within {} over [1, 1000]: "
                         "<code>{}</code>. The dotted curve is the closed form itself against an independent adaptive "
                         "quadrature of Int(n): |Δ| ≤ {} (where it is 0 in double, the point is not drawn).",
                         show(-100 * paper_1000, 3), best.size, show(worst_exact, 2), shown(best.formula),
                         show(worst_closed, 2)),
             "specula normalize --model log --n 1:1000@400:log --compare log-paper", context.save(table));
}

}  // namespace

Section normalization_section(Context& context) {
  context.progress("Fig. 5: the normalization table");
  std::string html = fig5(context);
  context.progress("Figs. 7-8: symbolic regression of the table");
  std::vector<double> rounded, exact;
  for (const double n : io::paper50()) {
    exact.push_back(lobes::log_rv(n));
    rounded.push_back(round3(exact.back()));
  }
  const Fits fits{run_fit(context, rounded, true), run_fit(context, exact, false)};
  html += fig8(context, fits);
  context.progress("Fig. 9: normalization error of the fitted formulas");
  html += fig9(context, fits);
  return {"normalization", "Figs. 5–9: the normalizing coefficient and its formula", html};
}

}  // namespace specula::report
