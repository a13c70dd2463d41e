#pragma once
// GGX: Trowbridge-Reitz D, Smith height-correlated masking-shadowing, any Fresnel of
// brdf/fresnel.h — Schlick's by default (Walter et al. 2007; Heitz 2014, eq. 99 for G₂).
// docs/math.md §2 `ggx`, docs/fresnel.md for the Fresnel kinds.
#include "specula/brdf/fresnel.h"
#include "specula/brdf/microfacet.h"

namespace specula {

struct Ggx {
  double alpha = 0.3;  ///< roughness α > 0
  fresnel::Channel fresnel{fresnel::Kind::schlick, 1.0};  ///< F(V·H); Schlick's F0 = 1 is F ≡ 1

  /// The lobe's width in θ_h (radians), a scale for the analysis's integrals: the roughness.
  double width() const noexcept { return alpha; }

  template <std::floating_point T>
  T operator()(const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v) const noexcept {
    const T a2 = T(alpha) * T(alpha);
    const auto d = [&](const microfacet::Inclination<T>& incl) {
      const T q = incl.cos2 * a2 + incl.sin2;  // cos²δ (α² − 1) + 1 without cancellation
      return a2 / (std::numbers::pi_v<T> * q * q);
    };
    return microfacet::smith_brdf(n, l, v, d, [&](T c) { return smith_lambda(c, a2); }, fresnel);
  }

  /// Λ(ω) = (−1 + √(1 + α² tan²θ))/2.
  template <std::floating_point T>
  static T smith_lambda(T cos_theta, T a2) noexcept {
    return (std::sqrt(T(1) + a2 * microfacet::tan2_from_cos(cos_theta)) - T(1)) / T(2);
  }
};

}  // namespace specula
