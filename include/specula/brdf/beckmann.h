#pragma once
// Beckmann with Smith's masking-shadowing: D = exp(−tan²δ/α²)/(π α² cos⁴δ), the height-correlated
// G₂ = 1/(1 + Λ(L) + Λ(V)) with Λ(ω) = (erf(a) − 1)/2 + e^(−a²)/(2a√π), a = 1/(α tan θ) (Walter
// et al. 2007, eq. 25–27; Heitz 2014, eq. 99 and §5.1), any Fresnel of brdf/fresnel.h. The
// microsurface of the random walk's Beckmann (walk/walk.h): its first bounce is this BRDF.
// docs/math.md §2 `beckmann`, docs/fresnel.md.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "specula/brdf/fresnel.h"
#include "specula/brdf/microfacet.h"

namespace specula {

struct Beckmann {
  double alpha = 0.3;  ///< roughness α > 0: the RMS slope, Cook-Torrance's m
  fresnel::Channel fresnel{fresnel::Kind::schlick, 1.0};  ///< F(V·H); Schlick's F0 = 1 is F ≡ 1

  /// The lobe's width in θ_h (radians), a scale for the analysis's integrals: the roughness.
  double width() const noexcept { return alpha; }

  template <std::floating_point T>
  T operator()(const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v) const noexcept {
    const auto d = [&](const microfacet::Inclination<T>& incl) {
      return microfacet::beckmann_unnormalized(incl, T(alpha)) / std::numbers::pi_v<T>;
    };
    return microfacet::smith_brdf(n, l, v, d, [&](T c) { return smith_lambda(c, T(alpha)); }, fresnel);
  }

  /// Λ(ω) = (erf(a) − 1)/2 + e^(−a²)/(2a√π) = (e^(−a²)/(a√π) − erfc(a))/2, a = cot θ / α;
  /// 0 at normal incidence.
  template <std::floating_point T>
  static T smith_lambda(T cos_theta, T alpha) noexcept {
    const T sin_theta = std::sqrt(std::max(T(0), T(1) - cos_theta * cos_theta));
    if (sin_theta <= T(0)) return T(0);
    const T a = cos_theta / (alpha * sin_theta);
    const T lambda = (std::exp(-a * a) / (a * std::sqrt(std::numbers::pi_v<T>)) - std::erfc(a)) / T(2);
    return std::max(lambda, T(0));  // the cancellation's rounding where Λ is below 1e-17 of its terms
  }
};

}  // namespace specula
