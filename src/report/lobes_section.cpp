// The paper's Figs. 2-4: the log lobe against c^n and Schlick's lobe, and their errors over n.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "sections.h"
#include "specula/analysis/error.h"
#include "specula/lobes/lobes.h"
#include "specula/catalogue/catalogue.h"
#include "specula/report/plot.h"

namespace specula::report {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

std::string fig2(Context& context) {
  constexpr double n = 20;
  const lobes::Lobe lobes[] = {lobes::Power<>{n}, lobes::Log<>{n}, lobes::Schlick<>{n}};
  const char* ids[] = {"phong", "log", "schlick"};
  DataTable table{"fig2-lobes", {"angle_deg", "phong", "log", "schlick"}, {}};
  Chart chart{"Fig. 2: the lobes at n = 20", {"angle from the mirror direction (degrees)", Scale::linear, 0, 90},
              {"F(cos θ)", Scale::linear, 0, 1}, {}};
  for (std::size_t k = 0; k < 3; ++k)
    chart.series.push_back({k == 0 ? "cosⁿθ (phong)" : k == 1 ? "F_log (log)" : "Schlick (schlick)", model_colour(ids[k]),
                            {}, {}, k == 2 ? Stroke::dashed : Stroke::solid});
  for (int i = 0; i <= 360; ++i) {
    const double angle = 0.25 * i, c = std::cos(angle * kDeg);
    std::vector<Cell> row{angle};
    for (std::size_t k = 0; k < 3; ++k) {
      const double f = lobes::eval(lobes[k], c);
      row.emplace_back(f);
      chart.series[k].x.push_back(angle);
      chart.series[k].y.push_back(f);
    }
    table.rows.push_back(std::move(row));
  }
  const double cutoff_deg = std::acos(std::exp2(-3 / n)) / kDeg;
  return context.svg_figure(
      "fig2-lobes", to_svg(chart),
      fmt::format("F<sub>log</sub> = max(0, 1 − ½ log₂(1 − n log₂ c)) follows cosⁿθ closely near the peak and "
                  "reaches 0 at θ = {:.2f}° (c₀ = 2<sup>−3/n</sup>), where cosⁿθ = 1/8; Schlick's c/(n − nc + c) "
                  "keeps a long tail.",
                  cutoff_deg),
      "specula eval --model log -p n=20 (and phong, schlick)", context.save(table));
}

struct Sweep {
  std::vector<double> n;
  std::vector<analysis::ApproximationError> log, schlick;
};

Sweep sweep(const Context& context) {
  Sweep s;
  s.n = log_spaced(1, 1000, context.quick() ? 13 : 97);
  s.n.push_back(2);  // where Schlick's lobe stops being exact
  std::sort(s.n.begin(), s.n.end());
  for (const double n : s.n) {
    s.log.push_back(analysis::approximation_error(lobes::Log<>{n}, lobes::Power<>{n}));
    s.schlick.push_back(analysis::approximation_error(lobes::Schlick<>{n}, lobes::Power<>{n}));
  }
  return s;
}

/// The range of one error over the sweep, for n ≥ n_min.
std::pair<double, double> range_of(const Sweep& s, const std::vector<analysis::ApproximationError>& errors,
                                   double analysis::ApproximationError::*member, double n_min = 0) {
  double lo = INFINITY, hi = -INFINITY;
  for (std::size_t i = 0; i < errors.size(); ++i) {
    if (s.n[i] < n_min) continue;
    lo = std::min(lo, errors[i].*member);
    hi = std::max(hi, errors[i].*member);
  }
  return {lo, hi};
}

Chart error_chart(const Sweep& s, const std::string& title, const std::string& y_label,
                  double analysis::ApproximationError::*member, double scale) {
  Chart chart{title, {"n (specular exponent)", Scale::log, 1, 1000}, {y_label, Scale::linear, 0, std::nullopt}, {}};
  chart.series.push_back({"F_log (log) vs cosⁿθ", model_colour("log"), s.n, {}});
  chart.series.push_back({"Schlick vs cosⁿθ", model_colour("schlick"), s.n, {}, Stroke::dashed});
  for (std::size_t i = 0; i < s.n.size(); ++i) {
    chart.series[0].y.push_back(s.log[i].*member * scale);
    chart.series[1].y.push_back(s.schlick[i].*member * scale);
  }
  chart.legend = Legend::bottom_right;
  return chart;
}

/// The user's lobe models (registered with --models) that have an exponent n to sweep.
std::vector<const ModelInfo*> user_lobes_with_n() {
  std::vector<const ModelInfo*> found;
  for (const auto& info : models())
    if (!info.is_builtin() && info.kind == ModelKind::lobe && info.find_param("n")) found.push_back(&info);
  return found;
}

/// The sweep's n values that `n` accepts.
std::vector<double> accepted(const ParamInfo& n, const std::vector<double>& values) {
  std::vector<double> kept;
  for (const double v : values)
    if (n.accepts(v)) kept.push_back(v);
  return kept;
}

/// The user's lobes against cosⁿθ, as Figs. 3-4 do for the paper's lobe: the same exact maxima.
std::string user_lobe_errors(Context& context, const std::vector<double>& sweep_n) {
  const auto lobes = user_lobes_with_n();
  if (lobes.empty()) return "";
  DataTable table{"user-lobe-errors",
                  {"model", "n", "max_abs", "argmax_abs_deg", "max_rel_epicenter", "max_rel_attenuation"}, {}};
  Chart chart{"Your lobes: max relative error in the epicenter zone", {"n (specular exponent)", Scale::log, 1, 1000},
              {"max relative error (%)", Scale::linear, 0, std::nullopt}, {}};
  std::vector<std::vector<std::string>> rows;
  for (const ModelInfo* info : lobes) {
    Series series{info->id + " vs cosⁿθ", model_colour(info->id), {}, {}};
    double worst_rel = 0, worst_abs = 0;
    const std::vector<double> ns = accepted(*info->find_param("n"), sweep_n);
    for (const double n : ns) {
      const auto e = analysis::approximation_error(make_model(info->id, {{"n", n}}).lobe(), lobes::Power<>{n});
      table.rows.push_back({info->id, n, e.max_abs, e.argmax_abs_deg, e.max_rel_epicenter, e.max_rel_attenuation});
      series.x.push_back(n);
      series.y.push_back(100 * e.max_rel_epicenter);
      worst_rel = std::max(worst_rel, e.max_rel_epicenter);
      worst_abs = std::max(worst_abs, e.max_abs);
    }
    rows.push_back({xml_escape(info->id), xml_escape(to_string(info->origin)), fmt::format("{}", ns.size()),
                    show(100 * worst_rel, 4) + " %", show(worst_abs, 6)});
    if (!ns.empty()) chart.series.push_back(std::move(series));
  }
  const std::string links = context.save(table);
  std::string html = "<h3 id=\"user-lobe-errors\">Your lobes against cosⁿθ</h3>\n<p>The lobe models of the model "
                     "files given with <code>--models</code>, each swept over the n values above that its range "
                     "accepts, with the same exact maxima.</p>\n";
  html += html_table({"model", "defined at", "n values", "max rel. error (epicenter)", "max |F − cosⁿθ|"}, rows, "models");
  if (!chart.series.empty()) {
    chart.legend = Legend::top_left;
    html += context.svg_figure("user-lobe-errors", to_svg(chart),
                               "Largest |F − cosⁿθ| / cosⁿθ where cosⁿθ ≥ ½, for each of your lobes.",
                               fmt::format("specula --models FILE error --model {} --reference phong --n 1:1000@97:log",
                                           lobes.front()->id),
                               links);
  }
  return html;
}

std::string figs3_4(Context& context) {
  const Sweep s = sweep(context);
  const std::string user_errors = user_lobe_errors(context, s.n);
  DataTable table{"fig3-4-errors",
                  {"n", "log_max_abs", "log_argmax_abs_deg", "log_max_rel_epicenter", "schlick_max_abs",
                   "schlick_argmax_abs_deg", "schlick_max_rel_epicenter"},
                  {}};
  for (std::size_t i = 0; i < s.n.size(); ++i)
    table.rows.push_back({s.n[i], s.log[i].max_abs, s.log[i].argmax_abs_deg, s.log[i].max_rel_epicenter,
                          s.schlick[i].max_abs, s.schlick[i].argmax_abs_deg, s.schlick[i].max_rel_epicenter});
  const std::string links = context.save(table);

  using E = analysis::ApproximationError;
  // At n = 1 Schlick's lobe is c itself: exact. Its ranges are quoted from n = 2 on.
  const auto [abs_lo, abs_hi] = range_of(s, s.log, &E::max_abs);
  const auto [rel_lo, rel_hi] = range_of(s, s.log, &E::max_rel_epicenter);
  const auto [srel_lo, srel_hi] = range_of(s, s.schlick, &E::max_rel_epicenter, 2);
  const auto [sabs_lo, sabs_hi] = range_of(s, s.schlick, &E::max_abs, 2);
  context.findings["log_max_abs_lo"] = {abs_lo, show(abs_lo, 10)};
  context.findings["log_max_abs_hi"] = {abs_hi, show(abs_hi, 10)};
  context.findings["log_max_rel_lo"] = {rel_lo, show(100 * rel_lo, 4) + " %"};
  context.findings["log_max_rel_hi"] = {rel_hi, show(100 * rel_hi, 4) + " %"};
  context.findings["schlick_max_rel_lo"] = {srel_lo, show(100 * srel_lo, 3) + " %"};
  context.findings["schlick_max_rel_hi"] = {srel_hi, show(100 * srel_hi, 3) + " %"};

  const std::string command = "specula error --model log --reference phong --n 1:1000@97:log (and --model schlick)";
  std::string html = context.svg_figure(
      "fig3-relative-error",
      to_svg(error_chart(s, "Fig. 3: max relative error in the epicenter zone", "max relative error (%)",
                         &E::max_rel_epicenter, 100)),
      fmt::format("Largest |F − cosⁿθ| / cosⁿθ where cosⁿθ ≥ ½. F<sub>log</sub>: {} % to {} % — the same for every n "
                  "(docs/math.md §3: in t = −n log₂ c both lobes are independent of n). Schlick: {} % to {} % for n ∈ [2, 1000], "
                  "growing with n (at n = 1 Schlick's lobe is c itself, exact). Maxima found exactly (dense sampling, then golden-section refinement).",
                  show(100 * rel_lo, 5), show(100 * rel_hi, 5), show(100 * srel_lo, 3), show(100 * srel_hi, 3)),
      command, links);
  html += context.svg_figure(
      "fig4-absolute-error",
      to_svg(error_chart(s, "Fig. 4: max absolute error", "max |F − cosⁿθ|", &E::max_abs, 1)),
      fmt::format("F<sub>log</sub>: {} to {} over n ∈ [1, 1000] — exactly 1/8, at t = 3 where F<sub>log</sub> reaches 0 "
                  "and cosⁿθ = 2<sup>−3</sup>. The paper reports 0.12 and draws a curve over n: that variation is its "
                  "sampling error. Schlick: {} to {} for n ∈ [2, 1000].",
                  show(abs_lo, 10), show(abs_hi, 10), show(sabs_lo, 4), show(sabs_hi, 4)),
      command, links);
  return html + user_errors;
}

}  // namespace

std::vector<double> log_spaced(double lo, double hi, int count) {
  std::vector<double> values;
  for (int i = 0; i < count; ++i)
    values.push_back(i == count - 1 ? hi : lo * std::pow(hi / lo, static_cast<double>(i) / (count - 1)));
  return values;
}

Section lobes_section(Context& context) {
  context.progress("Figs. 2-4: the lobes and their errors");
  return {"lobes", "Figs. 2–4: the logarithmic lobe against cosⁿθ",
          "<p>The paper's lobe F<sub>log</sub> approximates Blinn-Phong's cosⁿθ with one logarithm pair instead of a "
          "power. Below, each lobe is evaluated by specula's lobe library and the errors are found exactly.</p>\n" +
              fig2(context) + figs3_4(context)};
}

}  // namespace specula::report
