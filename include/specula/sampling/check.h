#pragma once
// Proof that a model's sampler is right (docs/sampling.md, "check --sampling"): the χ²
// goodness-of-fit test that Mitsuba 3 and pbrt-v4 run on their BSDFs, and the properties a path
// tracer relies on, at several incidence angles.
//
// For each θ_i: `samples` draws of Sampler::sample are binned on an equal-area grid over the
// hemisphere (uniform in cos θ_o and φ_o); the expected count of each cell is `samples` times the
// integral of Sampler::pdf over the cell, by adaptive Gauss-Legendre cubature (cells that contain
// the lobe's peak are refined down to its width). Cells expected below 5 are pooled (with those the
// cubature found empty), Pearson's χ²
// has (bins − 1) degrees of freedom and its p-value is the regularized upper incomplete gamma
// function Q(dof/2, χ²/2). The test passes at θ_i when p ≥ α_θ, α_θ = 1 − (1 − α)^(1/angles)
// (Šidák: the chance that any angle of a correct sampler fails is α). Besides:
//   - every sample lies in the hemisphere, with a finite pdf > 0 and weight = f·cos θ_o/pdf
//     (relative 1e-9, f and pdf evaluated again);
//   - pdf > 0 wherever f > 0 (at every cubature node);
//   - ∫ pdf over the hemisphere ≤ 1 + 1e-5 (+ the cubature's error estimate);
//   - the mean weight equals the cubature albedo ρ(θ_i) within z_θ standard errors (z_θ the
//     normal quantile of the same α_θ, two-sided) plus 1e-8 ρ.
// A model with f < 0 or f not finite (inf, NaN) at a sample fails there at once: such a density
// cannot be sampled, and the χ² and albedo checks mean nothing for it, so the check stops at that
// angle.
// Deterministic for a seed: samples come in blocks with seeds of their own, whatever the threads.
#include <cstdint>
#include <string>
#include <vector>

#include "specula/models/model.h"
#include "specula/sampling/sampler.h"

namespace specula::sampling {

/// The documented size of a check: at most 20 angles and 3e7 samples over all of them
/// (log-normalized, the slowest built-in sampler, drew and binned 5e7 in 106 s on a 2-core machine
/// at load average 7). Every interface (specula check --sampling, import specula) keeps to these.
inline constexpr std::size_t kMaxSamplingAngles = 20;
inline constexpr std::size_t kMaxSamplingTotal = 30'000'000;

struct SamplingCheckOptions {
  std::vector<double> theta_deg{0, 30, 60, 80, 89};
  std::size_t samples = 1'000'000;
  std::uint64_t seed = 1;
  int cos_bins = 32;  ///< grid resolution in cos θ_o; φ_o has twice as many
  double alpha = 0.01;
};

struct AngleCheck {
  double theta_deg = 0;
  std::size_t valid_samples = 0;
  double chi2 = 0;
  int dof = 0;
  double p_value = 0;
  double alpha = 0;               ///< α_θ (Šidák)
  double pdf_integral = 0;        ///< ∫ pdf over the hemisphere
  double pdf_integral_error = 0;  ///< the cubature's error estimate of it
  double mean_weight = 0, standard_error = 0;
  double albedo = 0;              ///< the cubature's ρ(θ_i)
  double z = 0;                   ///< |mean − ρ| / standard error allowed
  std::size_t outside = 0;        ///< samples outside the hemisphere, or with pdf ≤ 0 or not finite
  std::size_t weight_mismatches = 0;
  std::size_t uncovered_nodes = 0;  ///< cubature nodes where f > 0 but pdf = 0
  std::size_t unexpected_samples = 0;  ///< samples in cells the cubature found empty (pooled)
  std::size_t negative_samples = 0;    ///< samples where f < 0: nothing else is checked then
  double min_f = 0;                    ///< the least f among them
  std::size_t non_finite_samples = 0;  ///< samples where f is inf or NaN: nothing else is checked then
  double max_weight = 0;
  /// cos_bins × 2 cos_bins histograms, row-major (cos θ_o rows from the horizon up, φ columns).
  std::vector<double> observed, expected;

  bool chi2_passes() const noexcept { return p_value >= alpha; }
  bool albedo_agrees() const noexcept;
  bool pdf_normalized() const noexcept { return pdf_integral <= 1 + pdf_integral_error + 1e-5; }
  bool f_invalid() const noexcept { return negative_samples > 0 || non_finite_samples > 0; }
  bool passes() const noexcept {
    return !f_invalid() && chi2_passes() && albedo_agrees() && pdf_normalized() && outside == 0 &&
           weight_mismatches == 0 && uncovered_nodes == 0;
  }
};

struct SamplingCheck {
  std::string method;  ///< Sampler::description()
  double table_error = 0;
  int cos_bins = 0;
  std::vector<AngleCheck> angles;

  bool passes() const noexcept;
};

/// What the check runs on: a Sampler's functions, or stand-ins (the tests break a sampler on
/// purpose to show that the check fails).
struct SamplerUnderTest {
  const Model* model = nullptr;  ///< f, the albedo and the lobe's width come from it
  SampleFunction sample;
  std::function<double(const Vec3& wi, const Vec3& wo)> pdf;
  std::string description;
  double table_error = 0;

  static SamplerUnderTest of(const Sampler& sampler);
};

/// Throws InvalidArgument for an angle outside [0°, 90°), no angles, samples outside [1e3, 1e8],
/// cos_bins outside [4, 128] or alpha outside (0, 0.5). The angles after one where f < 0 at a
/// sample are not checked (the result ends there).
SamplingCheck check_sampling(const SamplerUnderTest& sampler, const SamplingCheckOptions& options = {});
SamplingCheck check_sampling(const Sampler& sampler, const SamplingCheckOptions& options = {});

}  // namespace specula::sampling
