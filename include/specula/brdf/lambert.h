#pragma once
// Lambert's diffuser (docs/math.md §1: the analytic reference, ρ(θ_i) = ρ for every θ_i).
#include <numbers>

#include "specula/brdf/vec3.h"

namespace specula {

/// The ideal diffuser f = ρ/π: the reference whose albedo is exactly ρ at every angle.
struct Lambert {
  double rho = 1.0;  ///< albedo ∈ [0, 1]

  /// A scale for the analysis's integrals: a diffuser has no lobe, so the whole hemisphere.
  double width() const noexcept { return std::numbers::pi / 2; }

  template <std::floating_point T>
  T operator()(const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v) const noexcept {
    return dot(n, l) > T(0) && dot(n, v) > T(0) ? T(rho) / std::numbers::pi_v<T> : T(0);
  }
};

}  // namespace specula
