// Beyond the paper: where energy goes. Directional albedo ρ(θ_i) of every model over the
// incidence angle, a conservation and reciprocity verdict per model and form (docs/math.md §1), and
// the lobes drawn in the plane of incidence as BRDF Explorer shows them.
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <numeric>

#include "sections.h"
#include "specula/analysis/albedo.h"
#include "specula/analysis/check.h"
#include "specula/analysis/parallel.h"
#include "specula/brdf/directions.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/report/plot.h"

namespace specula::report {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
/// ρ at the curve's last angle (89.9°) below this fraction of the largest ρ is a loss at grazing.
constexpr double kGrazingLoss = 0.5;

/// The curve's angles: every 5° (15° in quick mode), then towards grazing. 89.9° is the costliest
/// angle of the microfacet models by far, so quick mode stops at 89°.
std::vector<double> incidence_degrees(bool quick) {
  std::vector<double> degrees;
  for (int d = 0; d <= 85; d += quick ? 15 : 5) degrees.push_back(d);
  const std::vector<double> grazing = quick ? std::vector<double>{85, 89} : std::vector<double>{87, 89, 89.5, 89.9};
  degrees.insert(degrees.end(), grazing.begin(), grazing.end());
  return degrees;
}

Form other(Form form) { return form == Form::rv ? Form::nh : Form::rv; }

/// "ρ(89.9°)": the albedo at an angle, as the page writes it.
std::string rho_at(double degrees) { return fmt::format("ρ({:g}°)", degrees); }

/// One model in one form: its albedo curve and its check.
struct Energy {
  Model model;
  bool own_form = true;  ///< false: a lobe model in the other form, its k made for its own
  std::vector<double> rho;  ///< at incidence_degrees
  analysis::CheckResult check;
  double grazing_deg = 0;  ///< the curve's last angle

  std::string form_text() const { return model.is_lobe() ? to_string(model.form()) : "—"; }
  bool normalized_lobe() const { return model.is_lobe() && model.info().normalization != Normalization::none; }
  /// The form k was computed for ("—" for bare lobes, k = 1, and full BRDFs).
  std::string made_for() const {
    return normalized_lobe() ? to_string(own_form ? model.form() : other(model.form())) : "—";
  }
  double grazing() const { return rho.back(); }
};

/// Every model at its defaults (n = 20 for lobes); lobe models in their own form, then the other.
std::vector<Energy> energy_entries() {
  std::vector<Energy> entries;
  for (const auto& info : models()) {
    entries.push_back({make_model(info.id), true, {}, {}});
    if (info.kind == ModelKind::lobe) entries.push_back({make_model(info.id, {}, other(info.form)), false, {}, {}});
  }
  return entries;
}

analysis::CheckOptions check_options(bool quick) {
  analysis::CheckOptions options;
  options.grid_step_deg = quick ? 15 : 1;
  options.grazing_deg = {};  // the grazing angles are the curve's, computed once (see measure)
  options.reciprocity_pairs = quick ? 1'000 : 10'000;
  return options;
}

/// ρ on the curve's angles and the check on a θ_i grid up to 89°; the largest ρ is the larger of
/// the check's (refined by golden section) and the curve's (which adds the grazing angles).
void measure(Energy& e, const std::vector<double>& degrees, const analysis::CheckOptions& options) {
  std::vector<double> radians;
  for (const double d : degrees) radians.push_back(d * kDeg);
  e.rho = analysis::albedo_curve(e.model, radians);
  e.grazing_deg = degrees.back();
  e.check = analysis::check(e.model, options);
  for (std::size_t i = 0; i < degrees.size(); ++i)
    if (e.rho[i] > e.check.max_albedo.value) e.check.max_albedo = {e.rho[i], degrees[i]};
  e.check.conserves_energy = e.check.max_albedo.value <= 1 + options.energy_tolerance;
}

std::vector<Energy> measure_energy(const Context& context) {
  std::vector<Energy> entries = energy_entries();
  const std::vector<double> degrees = incidence_degrees(context.quick());
  const analysis::CheckOptions options = check_options(context.quick());
  std::vector<std::size_t> index(entries.size());
  std::iota(index.begin(), index.end(), std::size_t{0});
  analysis::parallel_map(std::span<const std::size_t>(index), [&](std::size_t i) {
    measure(entries[i], degrees, options);
    return 0;
  });
  return entries;
}

struct Verdict {
  std::string css_class, text;
};

Verdict verdict(const Energy& e) {
  const auto& max = e.check.max_albedo;
  if (!e.check.conserves_energy)
    return {"bad", fmt::format("gains energy (max ρ = {} at {}°)", show(max.value, 4), show(max.theta_deg, 3))};
  if (e.grazing() < kGrazingLoss * max.value)
    return {"ok", fmt::format("conserves; loses energy at grazing ({} = {})", rho_at(e.grazing_deg), show(e.grazing(), 3))};
  return {"ok", "conserves"};
}

const Energy& find(const std::vector<Energy>& entries, std::string_view id) {
  for (const auto& e : entries)
    if (e.own_form && e.model.id() == id) return e;
  throw InvalidArgument(fmt::format("energy: no model '{}'", id));
}

void record_findings(Context& context, const std::vector<Energy>& entries) {
  const auto& log = find(entries, "log-normalized").check.max_albedo;
  context.findings["log_normalized_max_albedo"] = {log.value, show(log.value, 10)};
  context.findings["log_normalized_max_albedo_deg"] = {log.theta_deg, show(log.theta_deg, 3)};
  const double lafortune = find(entries, "phong-lafortune").check.albedo_normal;
  context.findings["lafortune_albedo_0"] = {lafortune, show(lafortune, 6)};
  const auto& ct = find(entries, "cook-torrance-1982").check.max_albedo;
  context.findings["ct1982_max_albedo"] = {ct.value, fmt::format("{} (at θ<sub>i</sub> = {}°)", show(ct.value, 4),
                                                                 show(ct.theta_deg, 3))};
}

Series albedo_series(const Energy& e, const std::vector<double>& degrees) {
  const std::string name = std::string(e.model.id()) + (e.own_form ? "" : " (k made for " + e.made_for() + ")");
  return {name, model_colour(e.model.id()), degrees, e.rho, e.own_form ? Stroke::solid : Stroke::dashed};
}

/// ρ = 1, the bound of energy conservation, across the chart.
Series bound_series() { return {"ρ = 1", "#999999", {0, 90}, {1, 1}, Stroke::dotted}; }

/// "a, b and c".
std::string listed(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}

/// "id (max ρ = 3.998 at 89.9°)".
std::string with_max(const Energy& e) {
  return fmt::format("{} (max ρ = {} at {}°)", e.model.id(), show(e.check.max_albedo.value, 4),
                     show(e.check.max_albedo.theta_deg, 3));
}

/// The smallest and largest ρ(0°) of the normalized lobes whose k was made for `made_for` and
/// which are used in the other form.
std::pair<double, double> foreign_form_range(const std::vector<Energy>& entries, Form made_for) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& e : entries)
    if (!e.own_form && e.normalized_lobe() && e.made_for() == to_string(made_for)) {
      lo = std::min(lo, e.check.albedo_normal);
      hi = std::max(hi, e.check.albedo_normal);
    }
  return {lo, hi};
}

std::string lobe_caption(const std::vector<Energy>& entries, Form form) {
  const auto [lo, hi] = foreign_form_range(entries, other(form));
  return fmt::format(
      "f = k·F({}) at n = 20. Solid: the models made for this form. Dashed: k made for the {} form, used here: "
      "ρ(0°) = {} to {}. At normal incidence N·H = cos(θ<sub>o</sub>/2), so the same F is about twice as wide in "
      "θ<sub>o</sub> about N·H as about R·V: a k is only valid in the form it was computed for.",
      form == Form::rv ? "R·V" : "N·H", to_string(other(form)), show(lo, 3), show(hi, 3));
}

/// ρ(θ_i) of the normalized lobe models in one form.
std::string lobe_chart(Context& context, const std::vector<Energy>& entries, Form form, const std::string& links) {
  const std::vector<double> degrees = incidence_degrees(context.quick());
  Chart chart{fmt::format("Directional albedo of the normalized lobes, {} form (n = 20)", to_string(form)),
              {"incidence angle θ_i (degrees)", Scale::linear, 0, 90}, {"ρ(θ_i)", Scale::linear, 0, std::nullopt}, {}};
  for (const auto& e : entries)
    if (e.normalized_lobe() && e.model.form() == form) chart.series.push_back(albedo_series(e, degrees));
  chart.series.push_back(bound_series());
  if (form == Form::rv) chart.y.max = 1.4;  // room above ρ = 1 for the legend
  chart.legend = Legend::top_right;
  chart.height = 440;
  return context.svg_figure(fmt::format("energy-albedo-{}", to_string(form)), to_svg(chart), lobe_caption(entries, form),
                            fmt::format("specula albedo --model log-normalized -p n=20 --form {} --theta "
                                        "0:85:5,87,89,89.5,89.9 (and every normalized lobe)",
                                        to_string(form)),
                            links);
}

std::string brdf_caption(const std::vector<Energy>& entries) {
  std::vector<std::string> gaining, conserving;
  for (const auto& e : entries) {
    if (e.model.is_lobe()) continue;
    if (e.check.conserves_energy)
      conserving.emplace_back(e.model.id());
    else
      gaining.push_back(with_max(e));
  }
  return fmt::format(
      "Log scale. Gain energy: {}. Conserve it: {}. Cook-Torrance as printed in 1982 has D without its 1/π, and "
      "1/π in front of D F G/((N·L)(N·V)) where the normalized form has 1/4 (docs/math.md §2).",
      gaining.empty() ? "none" : listed(gaining), listed(conserving));
}

std::string brdf_chart(Context& context, const std::vector<Energy>& entries, const std::string& links) {
  const std::vector<double> degrees = incidence_degrees(context.quick());
  Chart chart{"Directional albedo of the full BRDFs (defaults)", {"incidence angle θ_i (degrees)", Scale::linear, 0, 90},
              {"ρ(θ_i)", Scale::log, 0.1, std::nullopt}, {}};
  for (const auto& e : entries)
    if (!e.model.is_lobe()) chart.series.push_back(albedo_series(e, degrees));
  chart.series.push_back(bound_series());
  chart.legend = Legend::top_left;
  chart.height = 440;
  return context.svg_figure(
      "energy-albedo-brdfs", to_svg(chart), brdf_caption(entries),
      "specula albedo --model cook-torrance-1982 --theta 0:85:5,87,89,89.5,89.9 (and every full BRDF)", links);
}

std::string energy_table(const std::vector<Energy>& entries) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& e : entries) {
    const Verdict v = verdict(e);
    rows.push_back({std::string(e.model.id()), e.form_text(), e.made_for(), show(e.check.albedo_normal, 6),
                    show(e.check.max_albedo.value, 6), show(e.check.max_albedo.theta_deg, 4), show(e.grazing(), 4),
                    show(e.check.max_asymmetry, 2), fmt::format("<td class=\"{}\">{}</td>", v.css_class, v.text)});
  }
  return html_table({"model", "form", "k made for", "ρ(0°)", "max ρ", "at θ<sub>i</sub> (°)",
                     rho_at(entries.front().grazing_deg), "reciprocity defect", "verdict"},
                    rows, "models verdicts");
}

DataTable albedo_data(const std::vector<Energy>& entries, const std::vector<double>& degrees) {
  DataTable table{"energy-albedo", {"model", "form", "own_form", "theta_i_deg", "albedo"}, {}};
  for (const auto& e : entries)
    for (std::size_t i = 0; i < degrees.size(); ++i)
      table.rows.push_back({std::string(e.model.id()), e.form_text(), e.own_form ? 1.0 : 0.0, degrees[i], e.rho[i]});
  return table;
}

DataTable check_data(const std::vector<Energy>& entries) {
  DataTable table{"energy-check",
                  {"model", "form", "own_form", "albedo_0", "max_albedo", "max_albedo_theta_deg", "albedo_89_9",
                   "max_asymmetry", "verdict"},
                  {}};
  for (const auto& e : entries)
    table.rows.push_back({std::string(e.model.id()), e.form_text(), e.own_form ? 1.0 : 0.0, e.check.albedo_normal,
                          e.check.max_albedo.value, e.check.max_albedo.theta_deg, e.grazing(), e.check.max_asymmetry,
                          verdict(e).text});
  return table;
}

// The lobes in the plane of incidence: f(L, V)·cos θ_o, V at θ_o (positive towards the mirror
// direction, negative on the light's side), L at θ_i on the other side of the normal.
constexpr const char* kPolarModels[] = {"log-normalized", "phong-normalized", "blinn-phong-normalized",
                                        "schlick-normalized", "ggx"};
constexpr double kPolarIncidence[] = {0, 30, 60};

std::vector<double> polar_angles(bool quick) {
  std::vector<double> angles;
  const double step = quick ? 1 : 0.25;
  for (double a = -89.75; a <= 89.75 + 1e-9; a += step) angles.push_back(a);
  return angles;
}

double projected_value(const Model& model, double theta_i_deg, double theta_o_deg) {
  const Vec3 n{0, 0, 1};
  const Vec3 l = from_spherical(-theta_i_deg * kDeg, 0.0), v = from_spherical(theta_o_deg * kDeg, 0.0);
  return model(n, l, v) * v.z;
}

std::string polar_figures(Context& context) {
  const std::vector<double> angles = polar_angles(context.quick());
  DataTable table{"energy-polar", {"theta_i_deg", "theta_o_deg"}, {}};
  std::vector<Model> polar_models;
  for (const char* id : kPolarModels) {
    table.columns.emplace_back(id);
    polar_models.push_back(make_model(id));
  }
  std::vector<PolarChart> charts;
  for (const double theta_i : kPolarIncidence) {
    PolarChart chart{fmt::format("θ_i = {}°", theta_i), "f · cos θ_o (1/sr)", {}, theta_i};
    for (const char* id : kPolarModels)  // GGX dashed: its colour is close to Blinn-Phong's
      chart.series.push_back(
          {id, model_colour(id), angles, {}, id == std::string_view("ggx") ? Stroke::dashed : Stroke::solid});
    for (const double a : angles) {
      std::vector<Cell> row{theta_i, a};
      for (std::size_t m = 0; m < polar_models.size(); ++m) {
        const double value = projected_value(polar_models[m], theta_i, a);
        chart.series[m].radius.push_back(value);
        row.emplace_back(value);
      }
      table.rows.push_back(std::move(row));
    }
    charts.push_back(std::move(chart));
  }
  const std::string links = context.save(table);
  std::string html = "<div class=\"grid\">\n";
  for (const auto& chart : charts)
    html += context.svg_figure(
        fmt::format("energy-polar-{:g}", chart.incident_deg), to_svg(chart),
        fmt::format("Light at θ<sub>i</sub> = {:g}° (dashed); radius f·cos θ<sub>o</sub> for V in the plane of "
                    "incidence, {}. n = 20 for the lobes, GGX at α = {:g}.",
                    chart.incident_deg,
                    chart.incident_deg == 0 ? std::string("where the mirror direction is the normal")
                                            : fmt::format("the mirror direction at +{:g}°", chart.incident_deg),
                    make_model("ggx").param("alpha")),
        fmt::format("specula eval --model ggx --theta-i {:g} --theta-o 0:89.75:0.25 --phi-o 180 (and --phi-o 0)",
                    chart.incident_deg),
        links);
  return html + "</div>\n";
}

/// What the table shows, in words: every number from the entries.
std::string summary(const std::vector<Energy>& entries) {
  std::vector<std::string> gaining_lobes;
  std::size_t own_lobes = 0;
  bool peak_at_normal = true;
  double worst_asymmetry = 0;
  for (const auto& e : entries) {
    worst_asymmetry = std::max(worst_asymmetry, e.check.max_asymmetry);
    if (!e.model.is_lobe() || !e.own_form) continue;
    ++own_lobes;
    peak_at_normal = peak_at_normal && e.check.max_albedo.theta_deg == 0;
    if (!e.check.conserves_energy) gaining_lobes.push_back(with_max(e));
  }
  const Energy& log = find(entries, "log-normalized");
  const auto [rv_lo, rv_hi] = foreign_form_range(entries, Form::rv);
  return fmt::format(
      "<p>In its own form, {} of the {} lobe models conserve energy at every incidence angle{}. {}"
      "log-normalized, the paper's model: max ρ = {} at θ<sub>i</sub> = {}°, {} = {}. Lafortune's (n + 1)/(2π) "
      "gives ρ(0°) = {} = (n + 1)/(n + 2) at n = 20: it leaves out the cos θ term. A k made for rv and used in nh "
      "gives ρ(0°) = {} to {}. The largest relative reciprocity defect of any model and form is {}.</p>\n",
      own_lobes - gaining_lobes.size(), own_lobes,
      gaining_lobes.empty() ? "" : "; gaining energy: " + listed(gaining_lobes),
      peak_at_normal ? "For every lobe model ρ is largest at normal incidence and falls towards grazing, where the "
                       "horizon cuts the lobe away — a loss, not a violation. "
                     : "",
      show(log.check.max_albedo.value, 10), show(log.check.max_albedo.theta_deg, 3), rho_at(log.grazing_deg),
      show(log.grazing(), 3), show(find(entries, "phong-lafortune").check.albedo_normal, 6), show(rv_lo, 4),
      show(rv_hi, 4), show(worst_asymmetry, 2));
}

}  // namespace

Section energy_section(Context& context) {
  context.progress("Energy: directional albedo of every model");
  const std::vector<Energy> entries = measure_energy(context);
  record_findings(context, entries);
  const analysis::CheckOptions options = check_options(context.quick());
  const std::string albedo_links = context.save(albedo_data(entries, incidence_degrees(context.quick())));
  const std::string check_links = context.save(check_data(entries));
  std::string html =
      "<p>The paper normalizes its lobe at normal incidence only. Here every model of specula is integrated at "
      "every incidence angle: the directional albedo ρ(θ<sub>i</sub>) = ∫ f(L, V) (N·V) dω<sub>V</sub> by "
      "deterministic adaptive cubature (8+ digits), at its defaults (n = 20 for the lobes).</p>\n";
  html += lobe_chart(context, entries, Form::rv, albedo_links);
  html += lobe_chart(context, entries, Form::nh, albedo_links);
  html += brdf_chart(context, entries, albedo_links);
  html += "<h3 id=\"energy-table\">Energy conservation and reciprocity, model by model</h3>\n" + summary(entries);
  html += energy_table(entries);
  html += fmt::format(
      "<p class=\"files\">max ρ: the larger of a {:g}° grid in θ<sub>i</sub> up to 89°, refined by golden-section "
      "search, and the curve's angles up to {:g}°; “loses energy at grazing” when {} < {:g}·max ρ; reciprocity "
      "defect: the largest |f(l, v) − f(v, l)| / max(f(l, v), f(v, l)) over {} random direction pairs. Files: {}. "
      "Regenerate: <code>specula check --model log-normalized</code> "
      "(and every model, with --form for the other form).</p>\n",
      options.grid_step_deg, entries.front().grazing_deg, rho_at(entries.front().grazing_deg), kGrazingLoss,
      options.reciprocity_pairs, check_links);
  html += "<h3 id=\"energy-polar\">The lobes in the plane of incidence</h3>\n" + polar_figures(context);
  return {"energy", "Beyond the paper: energy at every incidence angle", html};
}

}  // namespace specula::report
