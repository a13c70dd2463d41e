#include "specula/analysis/error.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <vector>

#include "../numeric/golden_section.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::analysis {
namespace {

constexpr double kLogCosEnd = 40;  // c = e^(−40): every lobe is below 1e-17 there
constexpr int kSamplesPerWidth = 64;
constexpr int kNearWidths = 64;
constexpr int kFarSamples = 2048;

using numeric::Maximum;

/// Maximizes g over [a, b] sampled at `grid` (sorted, within [a, b]): the best sample, then
/// golden-section search in the bracket of its neighbours.
template <class G>
Maximum maximize(const G& g, const std::vector<double>& grid) {
  check_interrupt();  // once per sweep of a grid (a few thousand cheap lobe evaluations)
  Maximum best;
  std::size_t best_index = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const double value = g(grid[i]);
    if (value > best.value) best = {grid[i], value}, best_index = i;
  }
  if (grid.size() < 3) return best;
  const double lo = grid[best_index == 0 ? 0 : best_index - 1];
  const double hi = grid[std::min(best_index + 1, grid.size() - 1)];
  const Maximum refined = numeric::golden_section_max(g, lo, hi, 1e-15 * (1 + hi));
  return refined.value > best.value ? refined : best;
}

/// Samples of [a, b]: dense (kSamplesPerWidth per width) up to kNearWidths widths, log-spaced
/// beyond, plus the given extra points (kinks).
std::vector<double> sample_grid(double a, double b, double width, std::vector<double> extra) {
  std::vector<double> grid;
  const double step = width / kSamplesPerWidth;
  const double near_end = std::min(b, a + kNearWidths * width);
  for (double u = a; u < near_end; u += step) grid.push_back(u);
  if (b > near_end) {
    const double ratio = std::pow(b / near_end, 1.0 / kFarSamples);
    for (double u = near_end; u < b; u *= ratio) grid.push_back(u);
  }
  grid.push_back(b);
  for (const double x : extra)  // the grid is sorted: put the kinks in their places
    if (x > a && x < b) grid.insert(std::lower_bound(grid.begin(), grid.end(), x), x);
  return grid;
}

double angle_deg(double u) { return 2 * std::asin(std::sqrt(-std::expm1(-u) / 2)) * 180 / std::numbers::pi; }

/// The u where the (decreasing) reference falls to `zone`, by bisection.
template <class L>
double zone_end(const L& reference, double zone, double end) {
  double lo = 0, hi = end;
  if (reference.at_log_cos(hi) >= zone) return hi;
  for (int i = 0; i < 200 && hi - lo > 1e-16 * hi; ++i) {
    const double mid = (lo + hi) / 2;
    (reference.at_log_cos(mid) >= zone ? lo : hi) = mid;
  }
  return lo;
}

template <class A, class B>
ApproximationError error_of(const A& model, const B& reference, double zone) {
  const double width = reference.half_max_log_cos();
  const double end = std::min(kLogCosEnd, reference.support_log_cos());
  const double model_end = model.support_log_cos();
  const double edge = zone_end(reference, zone, end);

  auto abs_diff = [&](double u) { return std::abs(model.at_log_cos(u) - reference.at_log_cos(u)); };
  auto rel_diff = [&](double u) {
    const double r = reference.at_log_cos(u);
    return r > 0 ? std::abs(model.at_log_cos(u) - r) / r : 0.0;
  };
  std::vector<double> kinks{model_end};
  for (const double x : lobes::kinks_log_cos(model)) kinks.push_back(x);
  for (const double x : lobes::kinks_log_cos(reference)) kinks.push_back(x);
  auto with = [&](std::vector<double> more) {
    more.insert(more.end(), kinks.begin(), kinks.end());
    return more;
  };
  ApproximationError e;
  const Maximum abs_max = maximize(abs_diff, sample_grid(0, kLogCosEnd, width, with({end})));
  e.max_abs = abs_max.value;
  e.argmax_abs_deg = angle_deg(abs_max.at);
  e.max_rel_epicenter = maximize(rel_diff, sample_grid(0, edge, width, kinks)).value;
  if (edge < end) e.max_rel_attenuation = maximize(rel_diff, sample_grid(edge, end, width, kinks)).value;
  return e;
}

}  // namespace

ApproximationError approximation_error(const lobes::Lobe& model, const lobes::Lobe& reference, double zone) {
  if (!(zone > 0 && zone < 1)) throw InvalidArgument(fmt::format("zone {} must be in (0, 1)", zone));
  return std::visit([zone](const auto& a, const auto& b) { return error_of(a, b, zone); }, model, reference);
}

}  // namespace specula::analysis
