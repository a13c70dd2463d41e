// Beyond the paper: what a model costs to evaluate on the machine writing the report, next to how
// far its lobe is from cⁿ (docs/math.md §3) — the trade the paper makes when it replaces a power by a
// logarithm pair. The chart comes from the lobe benchmark (cost/lobe_cost.h, `specula bench`):
// each lobe through the scalar lobe (libm) and the SIMD exact and fast tiers; the table below it
// times every model of the catalogue through the registry, one f(N, L, V) per call.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <optional>
#include <random>

#include "sections.h"
#include "specula/analysis/error.h"
#include "specula/brdf/directions.h"
#include "specula/cost/lobe_cost.h"
#include "specula/exceptions.h"
#include "specula/families/families.h"
#include "specula/catalogue/catalogue.h"
#include "specula/report/plot.h"

namespace specula::report {
namespace {

constexpr std::size_t kPairs = 4096;
constexpr int kTrials = 5;  // the fastest trial is reported: other work on the machine only slows trials down

struct Pair {
  Vec3 l, v;
};

/// L uniform over the hemisphere; V at an angle (π/2)·x² from the mirror direction, x uniform —
/// half the pairs within 22.5° of it, as shading evaluates a specular lobe around its highlight
/// (bench/lobes_bench.cpp's "peaked" cosines). V below the horizon is mirrored above it.
std::vector<Pair> direction_pairs() {
  std::mt19937_64 rng(20231105u);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const Vec3 n{0, 0, 1};
  std::vector<Pair> pairs;
  for (std::size_t i = 0; i < kPairs; ++i) {
    const Vec3 l = from_spherical(std::acos(uniform(rng)), 2 * std::numbers::pi * uniform(rng));
    const Vec3 r = reflect(l, n);
    const double x = uniform(rng), away = std::numbers::pi / 2 * x * x, around = 2 * std::numbers::pi * uniform(rng);
    const Vec3 t = normalized(std::abs(r.z) < 0.9 ? cross(r, n) : cross(r, Vec3{1, 0, 0}));
    const Vec3 b = cross(r, t);
    Vec3 v = r * std::cos(away) + (t * std::cos(around) + b * std::sin(around)) * std::sin(away);
    v.z = std::abs(v.z);
    pairs.push_back({l, normalized(v)});
  }
  return pairs;
}

/// Makes a value observable so that the loop computing it cannot be dropped (the empty asm of
/// benchmark::DoNotOptimize).
void keep(double value) { asm volatile("" : : "r,m"(value) : "memory"); }

/// ns per f(N, L, V) over one trial: as many passes over the pairs as fill `trial_ns`.
double time_trial(const Model& model, const std::vector<Pair>& pairs, double trial_ns) {
  using Clock = std::chrono::steady_clock;
  const Vec3 n{0, 0, 1};
  double sum = 0, elapsed = 0;
  std::size_t evaluations = 0;
  const auto start = Clock::now();
  do {
    for (const Pair& p : pairs) sum += model(n, p.l, p.v);
    evaluations += pairs.size();
    elapsed = std::chrono::duration<double, std::nano>(Clock::now() - start).count();
  } while (elapsed < trial_ns);
  keep(sum);
  return elapsed / static_cast<double>(evaluations);
}

struct Cost {
  Model model;
  double ns = INFINITY;
  std::optional<double> max_abs_error;  ///< the lobe's against cⁿ at the same n (lobe models)
};

/// Every model's fastest of kTrials trials. The trials go round the models in turn, after an
/// untimed warm-up round, so that a disturbance from other work on the machine hits one trial
/// of several models rather than every trial of one.
void time_models(std::vector<Cost>& costs, double trial_ns) {
  const std::vector<Pair> pairs = direction_pairs();
  for (auto& c : costs) time_trial(c.model, pairs, trial_ns / 4);
  for (int trial = 0; trial < kTrials; ++trial)
    for (auto& c : costs) c.ns = std::min(c.ns, time_trial(c.model, pairs, trial_ns));
}

std::vector<Cost> measure_costs(const Context& context) {
  std::vector<Cost> costs;
  for (const auto& info : models()) {
    Cost c{make_model(info.id), INFINITY, std::nullopt};
    if (c.model.is_lobe() && info.find_param("n"))
      c.max_abs_error = analysis::approximation_error(c.model.lobe(), lobes::Power<>{c.model.param("n")}).max_abs;
    costs.push_back(std::move(c));
  }
  time_models(costs, (context.quick() ? 1e6 : 20e6) / kTrials);
  return costs;
}

/// Models sharing a lobe and a form differ only in k: one point each, labelled with every id.
struct Point {
  std::string family;
  Form form;
  std::vector<std::string> ids;
  double error = 0;
  std::vector<double> ns;
};

std::vector<Point> points_by_lobe(const std::vector<Cost>& costs) {
  std::vector<Point> points;
  for (const auto& c : costs) {
    if (!c.max_abs_error) continue;
    const std::string family(families::family_name(c.model.lobe()));
    const Form form = c.model.form();
    auto same = std::find_if(points.begin(), points.end(), [&](const Point& p) {
      return p.family == family && p.form == form && p.error == *c.max_abs_error;
    });
    if (same == points.end()) same = points.insert(points.end(), Point{family, form, {}, *c.max_abs_error, {}});
    same->ids.emplace_back(c.model.id());
    same->ns.push_back(c.ns);
  }
  return points;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 ? values[mid] : (values[mid - 1] + values[mid]) / 2;
}

std::string join(const std::vector<std::string>& ids) {
  std::string out;
  for (const auto& id : ids) out += (out.empty() ? "" : ", ") + id;
  return out;
}

const Cost& cost_of(const std::vector<Cost>& costs, std::string_view id) {
  const auto it = std::find_if(costs.begin(), costs.end(), [&](const Cost& c) { return c.model.id() == id; });
  if (it == costs.end()) throw InvalidArgument(fmt::format("cost: no model '{}'", id));
  return *it;
}

constexpr cost::Path kPaths[] = {cost::Path::scalar, cost::Path::exact, cost::Path::fast};

/// The registry id whose colour a lobe family takes in every figure: its first model's.
std::string_view colour_id(const families::Family& family) { return family.models.front().id; }

/// The colour of the benchmark's lobe `i` (Result::lobes: the lobe families in simd::Family
/// order, then the user's lobes): a family takes its first model's colour, a user lobe its own.
std::string lobe_colour(const cost::Result& r, std::size_t i) {
  if (i >= families::kLobeFamilyCount) return model_colour(r.lobes[i]);
  return model_colour(colour_id(*families::kFamilies[i]));
}

/// The index of the lobe named `lobe` in Result::lobes.
std::size_t lobe_index(const cost::Result& r, std::string_view lobe) {
  return static_cast<std::size_t>(std::find(r.lobes.begin(), r.lobes.end(), lobe) - r.lobes.begin());
}

/// One point per lobe and path (float, in cache, one core): ns per evaluation against the
/// lobe's max |F − cⁿ|, the three paths of a lobe joined; cⁿ itself (error 0) as vertical lines.
Chart cost_chart(const cost::Result& r) {
  Chart chart{fmt::format("Accuracy against cost: lobes at n = {}, scalar libm and SIMD ({})", r.settings.n, r.machine.target),
              {"cost (ns per evaluation, float, in cache, one core)", Scale::log, std::nullopt, std::nullopt},
              {"max |F − cⁿ| (the lobe against Phong's)", Scale::log, std::nullopt, std::nullopt}, {}};
  double y_lo = INFINITY, y_hi = 0;
  for (std::size_t i = 1; i < r.lobes.size(); ++i) {  // 0 is cⁿ itself: the dashed lines below
    if (!(r.error_vs_power[i] > 0)) continue;           // no error against cⁿ to place it by
    Series s{r.lobes[i], lobe_colour(r, i), {}, {}, Stroke::solid, true, {}};
    for (const auto path : kPaths) {
      s.x.push_back(r.at(r.lobes[i], path, true).cache_ns);
      s.y.push_back(r.error_vs_power[i]);
      s.point_labels.push_back(cost::to_string(path));
    }
    y_lo = std::min(y_lo, r.error_vs_power[i]);
    y_hi = std::max(y_hi, r.error_vs_power[i]);
    chart.series.push_back(std::move(s));
  }
  chart.y.min = std::pow(10, std::floor(std::log10(y_lo)));
  chart.y.max = std::pow(10, std::ceil(std::log10(y_hi)));
  for (const auto path : kPaths) {
    const double ns = r.at(simd::Family::power, path, true).cache_ns;
    chart.series.push_back({path == cost::Path::scalar ? "cⁿ itself (phong): exact; libm, SIMD exact, SIMD fast" : "",
                            model_colour("phong"), {ns, ns}, {*chart.y.min, *chart.y.max}, Stroke::dashed});
  }
  chart.legend = Legend::bottom_left;
  chart.width = 720;
  chart.height = 440;
  return chart;
}

std::string bench_table(const cost::Result& r) {
  std::vector<std::vector<std::string>> rows;
  for (std::size_t i = 0; i < r.lobes.size(); ++i)
    for (const auto path : kPaths) {
      const cost::Measurement& m = r.at(r.lobes[i], path, true);
      const double scalar = r.at(r.lobes[i], cost::Path::scalar, true).cache_ns;
      rows.push_back({xml_escape(r.lobes[i]), cost::to_string(path), show(m.cache_ns, 3),
                      show(scalar / m.cache_ns, 3) + "×", show(m.evals_per_s_per_core(), 3), show(m.max_rel_error, 2),
                      show(r.error_vs_power[i], 4)});
    }
  return html_table({"lobe", "path", "ns per evaluation (float)", "× scalar", "evaluations/s per core",
                     "max relative error vs scalar double (F ≥ 10⁻³)", "max |F − cⁿ|"},
                    rows, "cost-simd");
}

DataTable bench_data(const cost::Result& r) {
  DataTable table{"cost-simd",
                  {"lobe", "path", "precision", "ns_per_eval", "evals_per_s_per_core", "max_rel_error", "max_abs_error",
                   "max_abs_error_vs_power"},
                  {}};
  for (const auto& m : r.rows)
    table.rows.push_back({m.lobe, std::string(cost::to_string(m.path)), std::string(m.single ? "float" : "double"),
                          m.cache_ns, m.evals_per_s_per_core(), m.max_rel_error, m.max_abs_error,
                          r.error_vs_power[lobe_index(r, m.lobe)]});
  return table;
}

std::string cost_table(const std::vector<Cost>& costs) {
  std::vector<std::vector<std::string>> rows;
  for (const auto& c : costs)
    rows.push_back({std::string(c.model.id()), to_string(c.model.info().kind),
                    c.model.is_lobe() ? to_string(c.model.form()) : "—", show(c.ns, 3),
                    c.max_abs_error ? show(*c.max_abs_error, 4) : "—"});
  return html_table({"model", "kind", "form", "ns per f(N, L, V)", "max |F − cⁿ| at n = 20"}, rows, "models");
}

DataTable cost_data(const std::vector<Cost>& costs) {
  DataTable table{"cost", {"model", "kind", "ns_per_eval", "max_abs_error_vs_power"}, {}};
  for (const auto& c : costs)
    table.rows.push_back({std::string(c.model.id()), std::string(to_string(c.model.info().kind)), c.ns,
                          c.max_abs_error ? *c.max_abs_error : NAN});
  return table;
}

/// Each lobe's time against Phong's cⁿ, in words.
std::string relative_costs(const std::vector<Cost>& costs) {
  const double phong = cost_of(costs, "phong").ns;
  std::string ratios;
  for (const char* id : {"log-normalized", "schlick-normalized", "schlick-modified", "gauss", "blinn-phong-normalized"})
    ratios += fmt::format("{}{} {}×", ratios.empty() ? "" : ", ", id, show(cost_of(costs, id).ns / phong, 2));
  const std::vector<Point> points = points_by_lobe(costs);
  const Point* cheapest = nullptr;
  const Point* closest = nullptr;  // the most accurate lobe that is not cⁿ itself
  for (const auto& p : points) {
    if (!cheapest || median(p.ns) < median(cheapest->ns)) cheapest = &p;
    if (p.error > 0 && (!closest || p.error < closest->error)) closest = &p;
  }
  return fmt::format("<p>Against phong's cⁿ ({} ns here): {}. The cheapest lobe is {}'s ({}; max |F − cⁿ| = {}); "
                     "the closest to cⁿ is {}'s ({}), at {}× phong's time.</p>\n",
                     show(phong, 3), ratios, cheapest->family, join(cheapest->ids), show(cheapest->error, 3),
                     closest->family, show(closest->error, 3), show(median(closest->ns) / phong, 2));
}

}  // namespace

Section cost_section(Context& context) {
  context.progress("Cost: evaluation time against accuracy");
  const cost::Result simd = cost::run(cost::Settings::report(context.quick()).with_registered_user_lobes());
  const std::vector<Cost> costs = measure_costs(context);
  const std::string links = context.save(cost_data(costs));
  const std::string simd_links = context.save(bench_data(simd));
  const std::string html =
      fmt::format("<p>A lobe is chosen for speed as much as for shape. The chart is specula's lobe benchmark "
                  "(<code>specula bench</code>, docs/simd.md): every lobe at n = {} over {} fixed cosines, mostly near "
                  "the highlight, through the scalar lobe (libm, one value per call) and through specula's SIMD batch "
                  "functions in their exact tier (within a few ulp of the scalar double lobe) and fast tier (within "
                  "10⁻⁴ where F ≥ 10⁻³), fastest of {} trials of {} ms.</p>\n",
                  simd.settings.n, simd.settings.cache_bytes / sizeof(float), simd.settings.trials,
                  1000 * simd.settings.trial_seconds) +
      context.svg_figure(
          "cost-accuracy", to_svg(cost_chart(simd)),
          "Timings are of the machine that wrote this report, at the time it wrote it (float lanes, one core, arrays "
          "in cache): compare them with each other, not with another machine. Each lobe's three points are the same "
          "lobe through three paths, so they share its error: its largest |F − cⁿ| over c ∈ [0, 1], found exactly "
          "(docs/math.md §3). cⁿ itself has no error: its three costs are the dashed lines.",
          "specula bench (the full benchmark: also double, streaming, all cores, limits)", simd_links) +
      bench_table(simd) +
      fmt::format("<p>Through the model catalogue instead, one call per value as a shader or a renderer calls it: "
                  "each model's f(N, L, V) over {} fixed pseudo-random direction pairs — L uniform over the hemisphere, "
                  "V mostly near the mirror direction — repeated for {} ms per model, fastest of {} trials (double "
                  "precision, registry dispatch included).</p>\n",
                  kPairs, context.quick() ? 1 : 20, kTrials) +
      relative_costs(costs) + cost_table(costs) + "<p>" + links + "</p>\n";
  return {"cost", "Beyond the paper: evaluation cost against accuracy", html};
}

}  // namespace specula::report
