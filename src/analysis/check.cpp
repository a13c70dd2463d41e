#include "specula/analysis/check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <tbb/parallel_for.h>

#include "../numeric/golden_section.h"
#include "specula/analysis/albedo.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::analysis {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr double kRefineTolerance = 1e-4;  // degrees
constexpr std::size_t kPairsPerCheck = 1024;  // reciprocity pairs between interrupt checks

/// Uniform on the upper hemisphere, including grazing directions.
Vec3 random_direction(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double z = uniform(rng), phi = 2 * std::numbers::pi * uniform(rng);
  const double s = std::sqrt(1 - z * z);
  return {s * std::cos(phi), s * std::sin(phi), z};
}

/// ρ on the grid of max_albedo: every step_deg below 89.5°, then the grazing angles beyond.
struct AlbedoGrid {
  std::vector<double> degrees, rho;
};

AlbedoGrid albedo_grid(const Model& model, double step_deg, const std::vector<double>& grazing_deg) {
  if (!(step_deg >= 0.01 && step_deg <= 45))
    throw InvalidArgument("the θ_i grid step must be in [0.01, 45] degrees");
  AlbedoGrid grid;
  std::vector<double>& degrees = grid.degrees;
  for (double d = 0; d < 89.5; d += step_deg) degrees.push_back(d);
  for (const double d : grazing_deg) {
    require_incidence_deg(d, "grazing angle");
    if (d > degrees.back()) degrees.push_back(d);
  }
  std::vector<double> radians(degrees.size());
  for (std::size_t i = 0; i < degrees.size(); ++i) radians[i] = degrees[i] * kDegree;
  grid.rho = albedo_curve(model, radians);
  return grid;
}

MaxAlbedo max_of(const Model& model, const AlbedoGrid& grid, double step_deg) {
  const std::vector<double>& degrees = grid.degrees;
  const std::vector<double>& rho = grid.rho;
  const auto best = static_cast<std::size_t>(std::max_element(rho.begin(), rho.end()) - rho.begin());
  MaxAlbedo result{rho[best], degrees[best]};
  // An interior maximum is refined; one at the grid's last point (89.9°) is the supremum's
  // approach to grazing, reported there. ρ is even in θ_i, so at 0° it is stationary: a maximum
  // there unless ρ rises within the first step.
  auto rho_at = [&](double deg) { return albedo(model, deg * kDegree).value; };
  const bool stationary_at_normal = best == 0 && rho_at(step_deg / 16) <= rho[0];
  if (best + 1 < degrees.size() && !stationary_at_normal) {
    const double lo = degrees[best == 0 ? 0 : best - 1], hi = degrees[best + 1];
    const auto refined = numeric::golden_section_max(rho_at, lo, hi, kRefineTolerance);
    if (refined.value > result.value) result = {refined.value, refined.at};
  }
  return result;
}

}  // namespace

MaxAlbedo max_albedo(const Model& model, double step_deg, const std::vector<double>& grazing_deg) {
  return max_of(model, albedo_grid(model, step_deg, grazing_deg), step_deg);
}

CheckResult check(const Model& model, const CheckOptions& options) {
  CheckResult r;
  r.albedo_normal = albedo(model, 0).value;
  const AlbedoGrid grid = albedo_grid(model, options.grid_step_deg, options.grazing_deg);
  r.max_albedo = max_of(model, grid, options.grid_step_deg);
  r.max_albedo.value = std::max(r.max_albedo.value, r.albedo_normal);
  if (r.max_albedo.value == r.albedo_normal) r.max_albedo.theta_deg = 0;

  const Vec3 n{0, 0, 1};
  std::mt19937_64 rng(options.seed);
  r.min_value = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < options.reciprocity_pairs; ++i) {
    if (i % kPairsPerCheck == 0) check_interrupt();
    const Vec3 l = random_direction(rng), v = random_direction(rng);
    const double f_lv = model(n, l, v), f_vl = model(n, v, l);
    r.min_value = std::min({r.min_value, f_lv, f_vl});
    const double scale = std::max(std::abs(f_lv), std::abs(f_vl));
    if (scale > 0) r.max_asymmetry = std::max(r.max_asymmetry, std::abs(f_lv - f_vl) / scale);
  }
  r.pairs = options.reciprocity_pairs;
  double tolerance = options.energy_tolerance;
  if (const Compensated* compensated = model.compensated()) {
    r.compensation_error = compensated->table->albedo_error;
    for (const double rho : grid.rho) r.max_deviation_from_one = std::max(r.max_deviation_from_one, std::abs(rho - 1));
    if (compensated->table->compensates()) tolerance += r.compensation_error;
  }
  r.conserves_energy = r.max_albedo.value <= 1 + tolerance;
  r.reciprocal = r.max_asymmetry <= options.reciprocity_tolerance;
  r.non_negative = r.min_value >= 0;
  return r;
}

double strict_coefficient(const Model& lobe_model, double step_deg) {
  return 1 / max_albedo(lobe_model.with_coef(1), step_deg).value;
}

}  // namespace specula::analysis
