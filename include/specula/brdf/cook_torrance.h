#pragma once
// Cook-Torrance microfacet BRDFs with the Beckmann distribution (docs/math.md §2).
#include "specula/brdf/directions.h"
#include "specula/brdf/microfacet.h"

namespace specula {

/// The paper's form (Cook & Torrance 1982): f = D F G / (π (N·L)(N·V)),
/// D = exp(−tan²δ/m²) / (m² cos⁴δ), dielectric Fresnel. D lacks the 1/π of a normalized NDF,
/// so the BRDF is 4× the modern one: with F ≡ 1 it reflects up to ~4× what it receives.
struct CookTorrance1982 {
  double m = 0.3;   ///< RMS slope m > 0
  double f0 = 1.0;  ///< reflectance at normal incidence ∈ [0, 1]; 1 gives F ≡ 1

  /// The lobe's width in θ_h (radians), a scale for the analysis's integrals: the roughness.
  double width() const noexcept { return m; }

  template <std::floating_point T>
  T operator()(const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v) const noexcept {
    const T nl = dot(n, l), nv = dot(n, v);
    if (nl <= T(0) || nv <= T(0)) return T(0);
    const Vec3T<T> h = half_vector(l, v);
    const T nh = dot(n, h), vh = dot(v, h);
    const T d = microfacet::beckmann_unnormalized(microfacet::inclination(n, h), T(m));
    const T f = microfacet::fresnel_dielectric(vh, T(f0));
    const T g = microfacet::g_vcavity(nh, nv, nl, vh);
    return d * f * g / (std::numbers::pi_v<T> * nl * nv);
  }
};

/// The modern normalized form: f = D F G / (4 (N·L)(N·V)), D = exp(−tan²δ/m²) / (π m² cos⁴δ),
/// Schlick's Fresnel (Walter et al. 2007 normalization of Cook-Torrance's Beckmann D).
struct CookTorrance {
  double m = 0.3;
  double f0 = 1.0;

  /// The lobe's width in θ_h (radians), a scale for the analysis's integrals: the roughness.
  double width() const noexcept { return m; }

  template <std::floating_point T>
  T operator()(const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v) const noexcept {
    const T nl = dot(n, l), nv = dot(n, v);
    if (nl <= T(0) || nv <= T(0)) return T(0);
    const Vec3T<T> h = half_vector(l, v);
    const T nh = dot(n, h), vh = dot(v, h);
    const T d = microfacet::beckmann_unnormalized(microfacet::inclination(n, h), T(m)) /
                std::numbers::pi_v<T>;
    const T f = microfacet::fresnel_schlick(vh, T(f0));
    const T g = microfacet::g_vcavity(nh, nv, nl, vh);
    return d * f * g / (T(4) * nl * nv);
  }
};

}  // namespace specula
