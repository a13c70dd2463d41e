#include "specula/analysis/energy.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <mutex>
#include <tbb/parallel_for.h>
#include <tuple>

#include "../numeric/piecewise.h"
#include "specula/analysis/parallel.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::analysis {
namespace {

// E_avg's quadrature: relative tolerance at the cubature's own noise, depth bounded so that a
// model whose E is noisy or kinked costs at most ~2000 albedos.
constexpr double kAverageTolerance = 1e-10;
constexpr unsigned kAverageMaxDepth = 5;
// The energy table's E_avg (table_average): an absolute tolerance on Simpson's error (the
// corrected value is 10–100× closer; what is left moves ms_scale, whose effect the table's
// measured albedo_error includes), and at most 4 halvings of its panels (1/32 wide in s).
constexpr double kTableAverageTolerance = 1e-7;
constexpr int kTableAverageLevels = 4;

/// E at each μ, in parallel; adds their integrand evaluations to `evaluations`.
std::vector<double> albedos_at(const Model& model, std::span<const double> mu, std::size_t& evaluations) {
  const std::vector<Albedo> albedos = parallel_map(mu, [&](double m) { return albedo_at_mu(model, m); });
  std::vector<double> values;
  for (const Albedo& a : albedos) {
    values.push_back(a.value);
    evaluations += a.evaluations;
  }
  return values;
}

/// g(s) = 6 s⁵ E(s³), E_avg's integrand in s = μ^(1/3), at a + k(b − a)/4 for k ≤ 4, and
/// Simpson's rule on it with steps (b − a)/2 and (b − a)/4.
struct Panel {
  double a, b;
  std::array<double, 5> g;

  double coarse() const noexcept { return (b - a) / 6 * (g[0] + 4 * g[2] + g[4]); }
  double fine() const noexcept { return (b - a) / 12 * (g[0] + 4 * g[1] + 2 * g[2] + 4 * g[3] + g[4]); }
};

double average_integrand(double s, double e) noexcept { return 6 * std::pow(s, 5) * e; }

/// The panels of width 1/32 whose points are the table's: s = k/128, nodes at even k > 0,
/// midpoints at odd k, and g(0) = 0.
std::vector<Panel> table_panels(const std::vector<double>& at_nodes, const std::vector<double>& at_mids) {
  constexpr std::size_t kSteps = 2 * EnergyTable::kNodes;
  auto g = [&](std::size_t k) {
    if (k == 0) return 0.0;
    return average_integrand(double(k) / kSteps, k % 2 == 0 ? at_nodes[k / 2 - 1] : at_mids[k / 2]);
  };
  std::vector<Panel> panels;
  for (std::size_t k = 0; k < kSteps; k += 4)
    panels.push_back({double(k) / kSteps, double(k + 4) / kSteps, {g(k), g(k + 1), g(k + 2), g(k + 3), g(k + 4)}});
  return panels;
}

/// Each panel's halves, their quarter points evaluated (all of them in parallel).
std::vector<Panel> split_panels(const Model& model, const std::vector<Panel>& panels, std::size_t& evaluations) {
  std::vector<Panel> halves;
  std::vector<double> s, mu;
  for (const Panel& p : panels) {
    const double m = (p.a + p.b) / 2;
    halves.push_back({p.a, m, {p.g[0], 0, p.g[1], 0, p.g[2]}});
    halves.push_back({m, p.b, {p.g[2], 0, p.g[3], 0, p.g[4]}});
  }
  for (const Panel& h : halves)
    for (const double x : {(3 * h.a + h.b) / 4, (h.a + 3 * h.b) / 4}) {
      s.push_back(x);
      mu.push_back(std::max(kMinMu, x * x * x));
    }
  const std::vector<double> e = albedos_at(model, mu, evaluations);
  for (std::size_t i = 0; i < halves.size(); ++i) {
    halves[i].g[1] = average_integrand(s[2 * i], e[2 * i]);
    halves[i].g[3] = average_integrand(s[2 * i + 1], e[2 * i + 1]);
  }
  return halves;
}

/// Simpson's value of a panel with Richardson's correction, and the correction: the error of the
/// uncorrected value, an upper bound on that of the corrected one.
std::pair<double, double> corrected(const Panel& p) noexcept {
  const double fine = p.fine(), correction = (fine - p.coarse()) / 15;
  return {fine + correction, std::abs(correction)};
}

/// The table's E_avg: adaptive Simpson in s with Richardson's correction, from panels whose points
/// are the table's own nodes and midpoints. While the corrections add up to more than the
/// tolerance, the panels whose correction exceeds their share of it are halved (their new points
/// are new albedos), down to kTableAverageLevels halvings.
Albedo table_average(const Model& model, const std::vector<double>& at_nodes, const std::vector<double>& at_mids) {
  Albedo total;
  std::vector<Panel> open = table_panels(at_nodes, at_mids);
  for (int level = 0; !open.empty(); ++level) {
    double open_error = 0;
    for (const Panel& p : open) open_error += corrected(p).second;
    const bool settled = total.error_estimate + open_error <= kTableAverageTolerance || level == kTableAverageLevels;
    std::vector<Panel> unsettled;
    for (const Panel& p : open) {
      const auto [value, error] = corrected(p);
      if (settled || error <= kTableAverageTolerance * (p.b - p.a)) {
        total.value += value;
        total.error_estimate += error;
      } else {
        unsettled.push_back(p);
      }
    }
    open = unsettled.empty() ? unsettled : split_panels(model, unsettled, total.evaluations);
  }
  return total;
}

/// What makes two models' tables the same: id, origin, parameter values, form and k.
using TableKey = std::tuple<std::string, std::string, std::vector<double>, int, double>;

TableKey key_of(const Model& m) {
  return {std::string(m.id()), to_string(m.info().origin), {m.params().begin(), m.params().end()},
          m.is_lobe() ? static_cast<int>(m.form()) : -1, m.is_lobe() ? m.coef() : 0.0};
}

struct TableCache {
  std::mutex mutex;
  std::map<TableKey, std::shared_ptr<const EnergyTable>> tables;
};

TableCache& table_cache() {
  static TableCache cache;
  return cache;
}

/// x^(1/power): the coordinate a lookup interpolates in.
double spaced(double x, double power) noexcept { return power == 1 ? x : std::pow(x, 1 / power); }

/// Index i and weight w with u(x) = (1 − w) u(v[i]) + w u(v[i + 1]), u(x) = x^(1/power), clamped
/// to the grid.
std::pair<std::size_t, double> bracket(std::span<const double> v, double x, double power) noexcept {
  if (v.size() < 2) return {0, 0.0};
  const auto upper = std::upper_bound(v.begin(), v.end(), x);
  const auto i = static_cast<std::size_t>(std::clamp<std::ptrdiff_t>(upper - v.begin() - 1, 0,
                                                                     static_cast<std::ptrdiff_t>(v.size()) - 2));
  const double a = spaced(v[i], power), b = spaced(v[i + 1], power);
  return {i, std::clamp((spaced(x, power) - a) / (b - a), 0.0, 1.0)};
}

/// The cells' midpoints in coordinates x^(1/power), or the one value.
std::vector<double> midpoints_or_values(std::span<const double> v, double power) {
  if (v.size() < 2) return {v.begin(), v.end()};
  std::vector<double> mid;
  for (std::size_t i = 0; i + 1 < v.size(); ++i)
    mid.push_back(std::pow((spaced(v[i], power) + spaced(v[i + 1], power)) / 2, power));
  return mid;
}

/// Runs cell(i) for i < count in parallel under the caller's limit, reporting progress.
template <class Cell>
void for_each_cell(std::size_t count, const Progress& progress, const Cell& cell) {
  std::atomic<std::size_t> done{0};
  std::mutex report;
  const auto one = [&](std::size_t i) {
    check_interrupt();
    cell(i);
    const std::size_t finished = ++done;
    if (progress) {
      const std::lock_guard lock(report);
      progress(finished, count);
    }
  };
  tbb::parallel_for(std::size_t{0}, count, carry_limit(one));
}

std::vector<Model> models_at(const ModelAt& model_at, std::span<const double> p) {
  std::vector<Model> models;
  for (const double value : p) models.push_back(model_at(value));
  return models;
}

}  // namespace

Albedo albedo_at_mu(const Model& model, double mu) {
  if (!(mu >= kMinMu && mu <= 1))
    throw InvalidArgument(fmt::format("mu = {} is outside [{:g}, 1]", mu, kMinMu));
  return albedo(model, std::acos(mu));
}

Albedo average_albedo(const Model& model) {
  // M+ms: its albedo is E_M(μ) + F_ms (1 − at(μ))₊ ms_scale, whose second part the table integrates
  // exactly; integrating the sum adaptively chased the interpolant's 64 kinks (2000 albedos).
  if (const Compensated* compensated = model.compensated(); compensated && !scales(compensated->scheme)) {
    const Albedo base = average_albedo(*compensated->base);
    const EnergyTable& table = *compensated->table;
    return {base.value + compensated->fresnel_scale * table.ms_scale * table.lost_average(), base.error_estimate,
            base.evaluations};
  }
  std::size_t evaluations = 0;
  auto integrand = [&](double s) {
    const Albedo e = albedo_at_mu(model, std::max(kMinMu, s * s * s));
    evaluations += e.evaluations;
    return average_integrand(s, e.value);
  };
  const auto e = numeric::integrate_pieces(integrand, 0, 1, 0.25, {0.5}, kAverageTolerance, kAverageMaxDepth);
  return {e.value, e.error, evaluations};
}

EnergyTable energy_table(const Model& base, std::size_t* evaluations) {
  std::vector<double> nodes(EnergyTable::kNodes), mids(EnergyTable::kNodes);
  for (std::size_t j = 0; j < nodes.size(); ++j) nodes[j] = EnergyTable::node_mu(j), mids[j] = EnergyTable::midpoint_mu(j);
  EnergyTable table;
  std::vector<double> abscissae = nodes;  // nodes and midpoints in one parallel loop
  abscissae.insert(abscissae.end(), mids.begin(), mids.end());
  std::size_t spent = 0;
  const std::vector<double> albedos = albedos_at(base, abscissae, spent);
  table.e.assign(albedos.begin(), albedos.begin() + std::ptrdiff_t(nodes.size()));
  const std::vector<double> at_mids(albedos.begin() + std::ptrdiff_t(nodes.size()), albedos.end());
  for (std::size_t j = 0; j < mids.size(); ++j)
    table.interpolation_error = std::max(table.interpolation_error, std::abs(table.at(mids[j]) - at_mids[j]));
  const Albedo average = table_average(base, table.e, at_mids);
  if (evaluations) *evaluations = spent + average.evaluations;
  table.e_avg = average.value;
  table.e_avg_error = average.error_estimate;
  table.ms_scale = table.e_avg < 1 ? table.lost_average() / (1 - table.e_avg) : 0;
  double deviation = 0;
  auto compensated = [&](double mu, double e) { return e + std::max(0.0, 1 - table.at(mu)) * table.ms_scale; };
  for (std::size_t j = 0; j < nodes.size(); ++j)
    deviation = std::max({deviation, std::abs(compensated(nodes[j], table.e[j]) - 1),
                          std::abs(compensated(mids[j], at_mids[j]) - 1)});
  table.albedo_error = EnergyTable::kErrorMargin * deviation;
  return table;
}

std::shared_ptr<const EnergyTable> cached_energy_table(const Model& base) {
  TableCache& cache = table_cache();
  const TableKey key = key_of(base);
  {
    const std::lock_guard lock(cache.mutex);
    if (const auto found = cache.tables.find(key); found != cache.tables.end()) return found->second;
  }
  // Built without the lock: the cubature runs parallel loops, whose waiting thread may pick up
  // another task that asks for a table. Two threads may build the same table; it is deterministic,
  // and the first one kept.
  auto table = std::make_shared<const EnergyTable>(energy_table(base));
  const std::lock_guard lock(cache.mutex);
  return cache.tables.try_emplace(key, std::move(table)).first->second;
}

void clear_energy_tables() {
  TableCache& cache = table_cache();
  const std::lock_guard lock(cache.mutex);
  cache.tables.clear();
}

double AlbedoLut::bilinear(double mu_value, double p_value) const noexcept {
  const auto [i, wp] = bracket(p, p_value, p_power);
  const auto [j, wm] = bracket(mu, mu_value, mu_power);
  auto row = [&](std::size_t r) {
    return mu.size() < 2 ? at(r, 0) : (1 - wm) * at(r, j) + wm * at(r, j + 1);
  };
  return p.size() < 2 ? row(0) : (1 - wp) * row(i) + wp * row(i + 1);
}

double AlbedoLut::linear_e_avg(double p_value) const noexcept {
  const auto [i, w] = bracket(p, p_value, p_power);
  return p.size() < 2 ? e_avg[0] : (1 - w) * e_avg[i] + w * e_avg[i + 1];
}

AlbedoLut albedo_lut(const ModelAt& model_at, std::span<const double> p, std::span<const double> mu, bool average,
                     const Progress& progress) {
  for (const double m : mu)
    if (!(m >= kMinMu && m <= 1)) throw InvalidArgument(fmt::format("mu = {} is outside [{:g}, 1]", m, kMinMu));
  const std::vector<Model> models = models_at(model_at, p);
  AlbedoLut lut{{p.begin(), p.end()}, {mu.begin(), mu.end()}, std::vector<double>(p.size() * mu.size()), {}, 1, 1};
  // The E_avg first (each costs ~100 cells), then the cells: one parallel loop over both.
  const std::size_t averages = average ? p.size() : 0;
  lut.e_avg.resize(averages);
  for_each_cell(averages + lut.e.size(), progress, [&](std::size_t k) {
    if (k < averages) {
      lut.e_avg[k] = average_albedo(models[k]).value;
    } else {
      const std::size_t cell = k - averages;
      lut.e[cell] = albedo_at_mu(models[cell / mu.size()], mu[cell % mu.size()]).value;
    }
  });
  return lut;
}

LutError lut_interpolation_error(std::span<const AlbedoLut> slices, std::span<const double> q, double q_power,
                                 const SliceAt& slice_at, const Progress& progress) {
  const AlbedoLut& lut = slices.front();
  const std::vector<double> q_mid = midpoints_or_values(q, q_power);
  const std::vector<double> p_mid = midpoints_or_values(lut.p, lut.p_power), mu_mid = midpoints_or_values(lut.mu, lut.mu_power);
  LutError error;
  for (const double qm : q_mid) {
    const auto [k, w] = bracket(q, qm, q_power);
    const AlbedoLut& a = slices[k];
    const AlbedoLut& b = slices[std::min(k + 1, slices.size() - 1)];
    const AlbedoLut exact = albedo_lut(slice_at(qm), p_mid, mu_mid, !lut.e_avg.empty(), progress);
    for (std::size_t i = 0; i < p_mid.size(); ++i) {
      for (std::size_t j = 0; j < mu_mid.size(); ++j) {
        const double lookup = (1 - w) * a.bilinear(mu_mid[j], p_mid[i]) + w * b.bilinear(mu_mid[j], p_mid[i]);
        error.e = std::max(error.e, std::abs(lookup - exact.at(i, j)));
      }
      if (!exact.e_avg.empty())
        error.e_avg = std::max(error.e_avg, std::abs((1 - w) * a.linear_e_avg(p_mid[i]) + w * b.linear_e_avg(p_mid[i]) -
                                                     exact.e_avg[i]));
    }
  }
  return error;
}

LutError lut_interpolation_error(const AlbedoLut& lut, const ModelAt& model_at, const Progress& progress) {
  const std::vector<double> p_mid = midpoints_or_values(lut.p, lut.p_power), mu_mid = midpoints_or_values(lut.mu, lut.mu_power);
  const AlbedoLut exact = albedo_lut(model_at, p_mid, mu_mid, !lut.e_avg.empty() && lut.p.size() > 1, progress);
  LutError error;
  for (std::size_t i = 0; i < p_mid.size(); ++i) {
    for (std::size_t j = 0; j < mu_mid.size(); ++j)
      error.e = std::max(error.e, std::abs(lut.bilinear(mu_mid[j], p_mid[i]) - exact.at(i, j)));
    if (!exact.e_avg.empty()) error.e_avg = std::max(error.e_avg, std::abs(lut.linear_e_avg(p_mid[i]) - exact.e_avg[i]));
  }
  return error;
}

}  // namespace specula::analysis
