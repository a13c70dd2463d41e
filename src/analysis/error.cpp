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

/// Maximizes g over [grid[first], grid[last]] whose values at the grid are `sampled`: the best
/// sample, then golden-section search in the bracket of its neighbours.
template <class G>
Maximum maximize(const G& g, const std::vector<double>& grid, const std::vector<double>& sampled, std::size_t first,
                 std::size_t last) {
  Maximum best;
  std::size_t best_index = first;
  for (std::size_t i = first; i <= last; ++i)
    if (sampled[i] > best.value) best = {grid[i], sampled[i]}, best_index = i;
  if (last - first < 2) return best;
  const double lo = grid[best_index == first ? first : best_index - 1];
  const double hi = grid[std::min(best_index + 1, last)];
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

  const auto relative = [](double value, double ref) { return ref > 0 ? std::abs(value - ref) / ref : 0.0; };
  auto abs_diff = [&](double u) { return std::abs(model.at_log_cos(u) - reference.at_log_cos(u)); };
  auto rel_diff = [&](double u) { return relative(model.at_log_cos(u), reference.at_log_cos(u)); };
  std::vector<double> extra{model_end, end, edge};
  for (const double x : lobes::kinks_log_cos(model)) extra.push_back(x);
  for (const double x : lobes::kinks_log_cos(reference)) extra.push_back(x);

  // One grid for the three maxima: each lobe is evaluated once per sample (the evaluations, two
  // exp at least, are nearly all of the cost), then each maximum reads its part of the grid.
  const std::vector<double> grid = sample_grid(0, kLogCosEnd, width, extra);
  std::vector<double> abs(grid.size()), rel(grid.size());
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const double value = model.at_log_cos(grid[i]), ref = reference.at_log_cos(grid[i]);
    abs[i] = std::abs(value - ref);
    rel[i] = relative(value, ref);
  }
  check_interrupt();
  const auto index_of = [&](double u) {
    return static_cast<std::size_t>(std::lower_bound(grid.begin(), grid.end(), u) - grid.begin());
  };
  const std::size_t edge_index = index_of(edge), end_index = index_of(end);
  ApproximationError e;
  const Maximum abs_max = maximize(abs_diff, grid, abs, 0, grid.size() - 1);
  e.max_abs = abs_max.value;
  e.argmax_abs_deg = angle_deg(abs_max.at);
  e.max_rel_epicenter = maximize(rel_diff, grid, rel, 0, edge_index).value;
  if (edge < end) e.max_rel_attenuation = maximize(rel_diff, grid, rel, edge_index, end_index).value;
  return e;
}

}  // namespace

ApproximationError approximation_error(const lobes::Lobe& model, const lobes::Lobe& reference, double zone) {
  if (!(zone > 0 && zone < 1)) throw InvalidArgument(fmt::format("zone {} must be in (0, 1)", zone));
  return std::visit([zone](const auto& a, const auto& b) { return error_of(a, b, zone); }, model, reference);
}

}  // namespace specula::analysis
