#pragma once
// An independent estimator of the directional albedo, by Monte Carlo with importance sampling,
// to cross-check the cubature (albedo.h). One-sample mixture of two strategies (balance
// heuristic): 80 % from a cosine-power lobe matched to the model's width — around R for lobes in
// `rv` form, over the half vector for `nh` lobes and microfacet BRDFs — and 20 % cosine-weighted
// over the hemisphere, which keeps the variance finite for heavy tails.
#include <cstdint>

#include "specula/models/model.h"

namespace specula::analysis {

struct MonteCarloEstimate {
  double mean = 0;
  double standard_error = 0;
  std::size_t samples = 0;
};

/// ρ(θ_i) (radians) from `samples` draws of a generator seeded with `seed`: the same inputs give
/// the same estimate.
MonteCarloEstimate albedo_monte_carlo(const Model& model, double theta_i, std::size_t samples,
                                      std::uint64_t seed = 1);

}  // namespace specula::analysis
