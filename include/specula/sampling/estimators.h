#pragma once
// The directional albedo ρ(θ_i) = ∫ f(ω_i, ω_o) cos θ_o dω_o by Monte Carlo with the estimators BRDF
// Explorer offers for its albedo view, so that each can be seen beside the exact cubature
// (analysis/albedo.h) with its standard error:
//   uniform   ω_o uniform on the hemisphere, pdf = 1/(2π)
//   cosine    ω_o cosine-weighted, pdf = cos θ_o / π
//   sampler   the model's own importance sampler (sampler.h), weight f cos θ_o / pdf
//   mis       one-sample multiple importance sampling of the sampler and the cosine, half each,
//             balance heuristic: f cos θ_o / (½ pdf_sampler + ½ pdf_cosine)
// Each is unbiased (the tests hold them to the cubature within 4 standard errors); they differ in
// variance, which is what the view shows.
#include <cstdint>
#include <string_view>

#include "specula/models/model.h"

namespace specula::sampling {

enum class Estimator { uniform, cosine, sampler, mis };
inline constexpr std::size_t kEstimatorCount = static_cast<std::size_t>(Estimator::mis) + 1;  // mis: the last

constexpr std::string_view to_string(Estimator e) noexcept {
  switch (e) {
    case Estimator::uniform: return "uniform";
    case Estimator::cosine: return "cosine";
    case Estimator::sampler: return "sampler";
    case Estimator::mis: return "mis";
  }
  return "";
}

struct AlbedoEstimate {
  double mean = 0;
  double standard_error = 0;  ///< the samples' standard deviation over √samples
};

/// ρ at θ_i (radians, [0, π/2)) from `samples` ≥ 2 draws of the stream `seed`: the same inputs
/// give the same estimate. Checks for an interrupt every 65 536 samples.
AlbedoEstimate albedo_estimate(const Model& model, double theta_i, Estimator estimator, std::uint64_t samples,
                               std::uint64_t seed = 1);

}  // namespace specula::sampling
