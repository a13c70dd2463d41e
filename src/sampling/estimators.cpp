// The albedo estimators of BRDF Explorer (estimators.h).
#include "specula/sampling/estimators.h"

#include <cmath>
#include <numbers>

#include "specula/brdf/directions.h"
#include "specula/interrupt/interrupt.h"
#include "specula/sampling/sampler.h"
#include "specula/sampling/seeds.h"

namespace specula::sampling {
namespace {

constexpr double kPi = std::numbers::pi;

/// ω_o cosine-weighted about +z (Malley's method) from two uniform numbers.
Vec3 cosine_direction(double u1, double u2) noexcept {
  const double r = std::sqrt(u1), phi = 2 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1))};
}

/// One sample's f cos θ_o / pdf.
double contribution(const Model& model, const Sampler& sampler, const Vec3& wi, Estimator estimator,
                    SplitMixStream& random) {
  const Vec3 n{0, 0, 1};
  const double u1 = random.uniform(), u2 = random.uniform();
  switch (estimator) {
    case Estimator::uniform: {
      const Vec3 wo = from_spherical(std::acos(1 - u1), 2 * kPi * u2);  // cos θ_o uniform in (0, 1]
      return model(n, wi, wo) * wo.z * 2 * kPi;
    }
    case Estimator::cosine: {
      const Vec3 wo = cosine_direction(u1, u2);
      return wo.z > 0 ? model(n, wi, wo) * kPi : 0.0;
    }
    case Estimator::sampler: {
      const Sample s = sampler.sample(wi, u1, u2);
      return s.valid() ? s.weight : 0.0;
    }
    case Estimator::mis: {
      const bool by_sampler = random.uniform() < 0.5;
      const Vec3 wo = by_sampler ? sampler.sample(wi, u1, u2).wo : cosine_direction(u1, u2);
      if (!(wo.z > 0)) return 0.0;
      const double pdf = 0.5 * sampler.pdf(wi, wo) + 0.5 * wo.z / kPi;
      return pdf > 0 ? model(n, wi, wo) * wo.z / pdf : 0.0;
    }
  }
  return 0;
}

}  // namespace

AlbedoEstimate albedo_estimate(const Model& model, double theta_i, Estimator estimator, std::uint64_t samples,
                               std::uint64_t seed) {
  const Sampler sampler(model);
  const Vec3 wi = from_spherical(theta_i, 0.0);
  SplitMixStream random(stream_key(seed, 0));
  double sum = 0, sum2 = 0;
  for (std::uint64_t k = 0; k < samples; ++k) {
    if (k % 65536 == 0) check_interrupt();
    const double x = contribution(model, sampler, wi, estimator, random);
    sum += x;
    sum2 += x * x;
  }
  const double n = static_cast<double>(samples), mean = sum / n;
  const double variance = std::max(0.0, (sum2 - n * mean * mean) / (n - 1));
  return {mean, std::sqrt(variance / n)};
}

}  // namespace specula::sampling
