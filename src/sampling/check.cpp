#include "specula/sampling/check.h"

#include <algorithm>
#include <array>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <tbb/parallel_for.h>

#include "specula/analysis/albedo.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::sampling {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMinExpected = 5;
const Vec3 kNormal{0, 0, 1};

struct Grid {
  int rows, cols;  ///< cos θ_o rows (from 0 to 1), φ_o columns (from 0 to 2π)
  double mu_step() const noexcept { return 1.0 / rows; }
  double phi_step() const noexcept { return 2 * kPi / cols; }
  int cell_of(const Vec3& wo) const noexcept {
    const int row = std::clamp(static_cast<int>(wo.z * rows), 0, rows - 1);
    double phi = std::atan2(wo.y, wo.x);
    if (phi < 0) phi += 2 * kPi;
    const int col = std::clamp(static_cast<int>(phi / phi_step()), 0, cols - 1);
    return row * cols + col;
  }
};

Vec3 direction(double mu, double phi) noexcept {
  const double s = std::sqrt(std::max(0.0, 1 - mu * mu));
  return {s * std::cos(phi), s * std::sin(phi), mu};
}

/// What a block of samples adds up to.
struct BlockTally {
  std::vector<double> histogram;
  double sum = 0, sum_sq = 0, max_weight = 0, min_f = 0;
  std::size_t valid = 0, outside = 0, mismatches = 0, negative = 0, non_finite = 0;
};

BlockTally tally(const SamplerUnderTest& sampler, const Vec3& wi, const Grid& grid, const std::vector<Sample>& samples) {
  BlockTally t;
  t.histogram.assign(std::size_t(grid.rows) * grid.cols, 0.0);
  for (const Sample& s : samples) {
    if (s.pdf == 0 && s.weight == 0) continue;  // no sample: counts as weight 0
    if (!(s.wo.z > 0) || !(s.pdf > 0) || !std::isfinite(s.pdf)) {
      ++t.outside;
      continue;
    }
    const double f = sampler.model->from_fixed(kNormal, wi, s.wo);
    if (!std::isfinite(f)) {
      ++t.non_finite;
      continue;
    }
    if (f < 0) {
      ++t.negative;
      t.min_f = std::min(t.min_f, f);
      continue;
    }
    if (!(s.weight >= 0) || !std::isfinite(s.weight)) {
      ++t.outside;
      continue;
    }
    const double expected = f * s.wo.z / sampler.pdf(wi, s.wo);
    if (!(std::abs(s.weight - expected) <= 1e-9 * std::max(s.weight, expected) + 1e-300)) ++t.mismatches;
    ++t.valid;
    ++t.histogram[grid.cell_of(s.wo)];
    t.sum += s.weight;
    t.sum_sq += s.weight * s.weight;
    t.max_weight = std::max(t.max_weight, s.weight);
  }
  return t;
}

// 4-point Gauss-Legendre on [−1, 1].
constexpr std::array<double, 4> kGaussX{-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
constexpr std::array<double, 4> kGaussW{0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};

/// A rectangle in (cos θ_o, φ_o).
struct Rect {
  double mu0, mu1, phi0, phi1;
};

/// ∫ pdf over one cell, adaptive: a rectangle's 4×4 Gauss-Legendre rule against the sum of its
/// halves' (along cos θ_o, φ_o or both), refined where they differ by more than the tolerance, and
/// where the lobe's peak is near and narrower than the rectangle — split then only along the
/// directions in which the rectangle is wider than the peak (at the pole, cos θ_o alone).
class CellIntegrator {
 public:
  CellIntegrator(const SamplerUnderTest& sampler, const Vec3& wi, double width, std::size_t samples)
      : sampler_(sampler), wi_(wi), peak_{-wi.x, -wi.y, wi.z}, width_(width), samples_(double(samples)) {}

  struct Result {
    double value = 0, error = 0;
  };

  Result integrate(const Rect& cell) { return refine(cell, rule(cell), 0); }
  std::size_t uncovered() const noexcept { return uncovered_; }

 private:
  static constexpr int kMaxDepth = 40;

  double rule(const Rect& r) {
    const double hm = (r.mu1 - r.mu0) / 2, cm = (r.mu1 + r.mu0) / 2, hp = (r.phi1 - r.phi0) / 2,
                 cp = (r.phi1 + r.phi0) / 2;
    double sum = 0;
    for (std::size_t i = 0; i < 4; ++i)
      for (std::size_t j = 0; j < 4; ++j) {
        const Vec3 wo = direction(cm + hm * kGaussX[i], cp + hp * kGaussX[j]);
        const double pdf = sampler_.pdf(wi_, wo);
        if (!(pdf > 0) && (*sampler_.model)(kNormal, wi_, wo) > 0) ++uncovered_;
        sum += kGaussW[i] * kGaussW[j] * pdf;
      }
    return sum * hm * hp;
  }

  struct Split {
    bool mu = false, phi = false;
  };

  /// The splits that bring the rectangle down to the peak's width where the peak is near.
  Split peak_split(const Rect& r) const {
    const double theta_lo = std::acos(std::min(1.0, r.mu1)), theta_hi = std::acos(std::max(0.0, r.mu0));
    const double mu_extent = theta_hi - theta_lo;
    const double phi_extent = (r.phi1 - r.phi0) * std::sin(theta_hi);
    const double size = std::hypot(mu_extent, phi_extent);
    // The angle from the peak to the rectangle: to its nearest corner, less its own size.
    double distance = kPi;
    for (double mu : {r.mu0, r.mu1})
      for (double phi : {r.phi0, r.phi1})
        distance = std::min(distance, std::acos(std::clamp(dot(direction(mu, phi), peak_), -1.0, 1.0)));
    if (distance > size + 4 * width_) {
      // The peak may still lie inside a rectangle whose corners are all far from it.
      const double peak_mu = peak_.z, peak_phi = kPi;
      const bool inside = peak_mu >= r.mu0 && peak_mu <= r.mu1 && peak_phi >= r.phi0 && peak_phi <= r.phi1;
      if (!inside) return {};
    }
    return {mu_extent > width_ / 4, phi_extent > width_ / 4};
  }

  std::vector<Rect> halves(const Rect& r, Split split) const {
    const double mm = (r.mu0 + r.mu1) / 2, pm = (r.phi0 + r.phi1) / 2;
    if (split.mu && split.phi)
      return {{r.mu0, mm, r.phi0, pm}, {r.mu0, mm, pm, r.phi1}, {mm, r.mu1, r.phi0, pm}, {mm, r.mu1, pm, r.phi1}};
    if (split.mu) return {{r.mu0, mm, r.phi0, r.phi1}, {mm, r.mu1, r.phi0, r.phi1}};
    return {{r.mu0, r.mu1, r.phi0, pm}, {r.mu0, r.mu1, pm, r.phi1}};
  }

  Result refine(const Rect& r, double coarse, int depth) {
    check_interrupt();  // a cell near a narrow peak may take thousands of refinements
    const Split peak = peak_split(r);
    const std::vector<Rect> parts = halves(r, peak.mu || peak.phi ? peak : Split{true, true});
    std::vector<double> values(parts.size());
    double fine = 0;
    for (std::size_t q = 0; q < parts.size(); ++q) fine += values[q] = rule(parts[q]);
    // Enough where the expected count is off by well under its own standard deviation.
    const double tolerance = 1e-3 * std::sqrt(std::max(fine, 1 / samples_) / samples_);
    const bool settled = std::abs(fine - coarse) <= tolerance && !peak.mu && !peak.phi;
    if (settled || depth == kMaxDepth) return {fine, std::abs(fine - coarse)};
    Result total;
    for (std::size_t q = 0; q < parts.size(); ++q) {
      const Result part = refine(parts[q], values[q], depth + 1);
      total.value += part.value;
      total.error += part.error;
    }
    return total;
  }

  const SamplerUnderTest& sampler_;
  Vec3 wi_, peak_;
  double width_, samples_;
  std::size_t uncovered_ = 0;
};

/// Pearson's χ² of observed against expected counts, cells expected below 5 pooled (as Mitsuba
/// 3's chi2.py). Cells the cubature found empty (no node with pdf > 0: outside the lobe's support,
/// or a sliver of it between the nodes) join the pool, their samples counted apart as well; a
/// sample where pdf() is 0 fails the per-sample checks instead.
void chi2_test(AngleCheck& a) {
  std::vector<std::size_t> order(a.expected.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return a.expected[i] < a.expected[j]; });
  double pooled_expected = 0, pooled_observed = 0, chi2 = 0;
  int bins = 0;
  for (std::size_t i : order) {
    const double e = a.expected[i], o = a.observed[i];
    if (e == 0) a.unexpected_samples += static_cast<std::size_t>(o);
    if (e < kMinExpected || pooled_expected > 0) {
      pooled_expected += e, pooled_observed += o;
      if (pooled_expected < kMinExpected) continue;
      chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
      pooled_expected = pooled_observed = 0;
    } else {
      chi2 += (o - e) * (o - e) / e;
    }
    ++bins;
  }
  if (pooled_expected > 0) {  // a remainder under 5: a bin of its own all the same
    chi2 += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
    ++bins;
  }
  a.chi2 = chi2;
  a.dof = std::max(1, bins - 1);
  a.p_value = boost::math::gamma_q(a.dof / 2.0, chi2 / 2);
}

void validate(const SamplingCheckOptions& o) {
  if (o.theta_deg.empty()) throw InvalidArgument("the sampling check needs at least one incidence angle");
  for (double t : o.theta_deg) analysis::require_incidence_deg(t, "theta-i");
  if (o.samples < 1000 || o.samples > 100'000'000)
    throw InvalidArgument(fmt::format("sample count {} is outside [1e3, 1e8]", o.samples));
  if (o.cos_bins < 4 || o.cos_bins > 128)
    throw InvalidArgument(fmt::format("grid resolution {} is outside [4, 128]", o.cos_bins));
  if (!(o.alpha > 0 && o.alpha < 0.5)) throw InvalidArgument(fmt::format("significance {} is outside (0, 0.5)", o.alpha));
}

AngleCheck check_angle(const SamplerUnderTest& sampler, const SamplingCheckOptions& o, std::size_t index, double alpha) {
  AngleCheck a;
  a.theta_deg = o.theta_deg[index];
  a.alpha = alpha;
  const double theta = radians(a.theta_deg);
  const Vec3 wi{std::sin(theta), 0, std::cos(theta)};
  const Grid grid{o.cos_bins, 2 * o.cos_bins};

  const std::size_t blocks = (o.samples + kSeedBlock - 1) / kSeedBlock;
  std::vector<BlockTally> tallies(blocks);
  const std::uint64_t angle_seed = o.seed + 0x5bd1e995ULL * index;
  tbb::parallel_for(std::size_t{0}, blocks, carry_limit([&](std::size_t b) {
                      check_interrupt();
                      const std::size_t count = std::min(kSeedBlock, o.samples - b * kSeedBlock);
                      tallies[b] = tally(sampler, wi, grid, draw_block(sampler.sample, wi, angle_seed, b, count));
                    }));
  a.observed.assign(std::size_t(grid.rows) * grid.cols, 0.0);
  double sum = 0, sum_sq = 0;
  for (const BlockTally& t : tallies) {  // in block order: the same sums for any thread count
    for (std::size_t c = 0; c < a.observed.size(); ++c) a.observed[c] += t.histogram[c];
    sum += t.sum, sum_sq += t.sum_sq;
    a.valid_samples += t.valid, a.outside += t.outside, a.weight_mismatches += t.mismatches;
    a.negative_samples += t.negative;
    a.non_finite_samples += t.non_finite;
    a.min_f = std::min(a.min_f, t.min_f);
    a.max_weight = std::max(a.max_weight, t.max_weight);
  }
  a.expected.assign(a.observed.size(), 0.0);
  if (a.f_invalid()) return a;  // f < 0 or not finite: the finding; χ² and albedo mean nothing
  const double n = double(o.samples);
  a.mean_weight = sum / n;
  a.standard_error = std::sqrt(std::max(0.0, sum_sq / n - a.mean_weight * a.mean_weight) / n);

  const double width = analysis::angular_width(*sampler.model);
  std::vector<CellIntegrator::Result> cells(a.observed.size());
  std::vector<std::size_t> uncovered(grid.rows, 0);
  tbb::parallel_for(0, grid.rows, carry_limit([&](int row) {
                      check_interrupt();
                      CellIntegrator integrator(sampler, wi, width, o.samples);
                      for (int col = 0; col < grid.cols; ++col)
                        cells[std::size_t(row) * grid.cols + col] = integrator.integrate(
                            {row * grid.mu_step(), (row + 1) * grid.mu_step(), col * grid.phi_step(),
                             (col + 1) * grid.phi_step()});
                      uncovered[row] = integrator.uncovered();
                    }));
  double integral_error = 0;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    a.expected[c] = cells[c].value * n;
    a.pdf_integral += cells[c].value;
    integral_error += cells[c].error;
  }
  a.pdf_integral_error = integral_error;
  a.uncovered_nodes = std::accumulate(uncovered.begin(), uncovered.end(), std::size_t{0});
  chi2_test(a);

  a.albedo = analysis::albedo(*sampler.model, theta).value;
  a.z = boost::math::quantile(boost::math::normal(), 1 - alpha / 2);
  return a;
}

}  // namespace

bool AngleCheck::albedo_agrees() const noexcept {
  return std::abs(mean_weight - albedo) <= z * standard_error + 1e-8 * albedo;
}

bool SamplingCheck::passes() const noexcept {
  return std::all_of(angles.begin(), angles.end(), [](const AngleCheck& a) { return a.passes(); });
}

SamplerUnderTest SamplerUnderTest::of(const Sampler& sampler) {
  return {&sampler.model(), [&sampler](const Vec3& wi, double u1, double u2) { return sampler.sample(wi, u1, u2); },
          [&sampler](const Vec3& wi, const Vec3& wo) { return sampler.pdf(wi, wo); }, sampler.description(),
          sampler.table_error()};
}

SamplingCheck check_sampling(const Sampler& sampler, const SamplingCheckOptions& options) {
  return check_sampling(SamplerUnderTest::of(sampler), options);
}

SamplingCheck check_sampling(const SamplerUnderTest& sampler, const SamplingCheckOptions& options) {
  validate(options);
  SamplingCheck result{sampler.description, sampler.table_error, options.cos_bins, {}};
  const double per_angle = 1 - std::pow(1 - options.alpha, 1.0 / double(options.theta_deg.size()));
  for (std::size_t i = 0; i < options.theta_deg.size(); ++i) {
    result.angles.push_back(check_angle(sampler, options, i, per_angle));
    if (result.angles.back().f_invalid()) break;
  }
  return result;
}

}  // namespace specula::sampling
