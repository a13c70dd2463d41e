#pragma once
// GGX: Trowbridge-Reitz D, Smith height-correlated masking-shadowing, Schlick Fresnel
// (Walter et al. 2007; Heitz 2014, eq. 99 for G₂). docs/math.md §2 `ggx`.
#include "specula/brdf/directions.h"
#include "specula/brdf/microfacet.h"

namespace specula {

struct Ggx {
  double alpha = 0.3;  ///< roughness α > 0
  double f0 = 1.0;     ///< reflectance at normal incidence ∈ [0, 1]

  /// The lobe's width in θ_h (radians), a scale for the analysis's integrals: the roughness.
  double width() const noexcept { return alpha; }

  template <std::floating_point T>
  T operator()(const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v) const noexcept {
    const T nl = dot(n, l), nv = dot(n, v);
    if (nl <= T(0) || nv <= T(0)) return T(0);
    const Vec3T<T> h = half_vector(l, v);
    const T vh = dot(v, h);
    const T a2 = T(alpha) * T(alpha);
    const auto incl = microfacet::inclination(n, h);
    const T q = incl.cos2 * a2 + incl.sin2;  // cos²δ (α² − 1) + 1 without cancellation
    const T d = a2 / (std::numbers::pi_v<T> * q * q);
    const T g = T(1) / (T(1) + smith_lambda(nl, a2) + smith_lambda(nv, a2));
    return d * microfacet::fresnel_schlick(vh, T(f0)) * g / (T(4) * nl * nv);
  }

  /// Λ(ω) = (−1 + √(1 + α² tan²θ))/2.
  template <std::floating_point T>
  static T smith_lambda(T cos_theta, T a2) noexcept {
    return (std::sqrt(T(1) + a2 * microfacet::tan2_from_cos(cos_theta)) - T(1)) / T(2);
  }
};

}  // namespace specula
