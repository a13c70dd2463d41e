#pragma once
// Shared pieces of microfacet BRDFs (docs/math.md §2, "Cook-Torrance parts").
#include <algorithm>

#include "specula/brdf/directions.h"
#include "specula/brdf/vec3.h"

namespace specula::microfacet {

/// sin²δ and cos²δ of the angle δ between the unit normal N and a vector h of any length
/// (scaled by |h|²); sin² from the cross product, exact near δ = 0 where 1 − cos²δ cancels.
template <std::floating_point T>
struct Inclination {
  T sin2, cos2;
  T tan2() const noexcept { return sin2 / cos2; }
};

template <std::floating_point T>
constexpr Inclination<T> inclination(const Vec3T<T>& n, const Vec3T<T>& h) noexcept {
  const T c = dot(n, h);
  const Vec3T<T> s = cross(n, h);
  const T norm = dot(h, h);
  return {dot(s, s) / norm, c * c / norm};
}

/// tan²θ of a unit direction ω from its cosine (grazing-safe enough for masking terms).
template <std::floating_point T>
constexpr T tan2_from_cos(T cos_theta) noexcept {
  const T c2 = cos_theta * cos_theta;
  return (T(1) - c2) / c2;
}

/// Beckmann's exp(−tan²δ/m²) / (m² cos⁴δ), without the 1/π of the normalized NDF.
template <std::floating_point T>
T beckmann_unnormalized(const Inclination<T>& h, T m) noexcept {
  return std::exp(-h.tan2() / (m * m)) / (m * m * h.cos2 * h.cos2);
}

/// A Smith microfacet BRDF, D(H) F(V·H) G₂ / (4 (N·L)(N·V)) with the height-correlated
/// G₂ = 1/(1 + Λ(N·L) + Λ(N·V)) (Heitz 2014, eq. 99); 0 below the horizon. `d` takes H's
/// Inclination, `lambda` a direction's cosine, `fresnel` the cosine V·H.
template <std::floating_point T, class D, class Lambda, class Fresnel>
T smith_brdf(const Vec3T<T>& n, const Vec3T<T>& l, const Vec3T<T>& v, const D& d, const Lambda& lambda,
             const Fresnel& fresnel) noexcept {
  const T nl = dot(n, l), nv = dot(n, v);
  if (nl <= T(0) || nv <= T(0)) return T(0);
  const Vec3T<T> h = half_vector(l, v);
  const T g = T(1) / (T(1) + lambda(nl) + lambda(nv));
  return d(inclination(n, h)) * fresnel(dot(v, h)) * g / (T(4) * nl * nv);
}

/// Cook & Torrance's V-cavity masking-shadowing G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H)).
template <std::floating_point T>
constexpr T g_vcavity(T nh, T nv, T nl, T vh) noexcept {
  return std::min({T(1), T(2) * nh * nv / vh, T(2) * nh * nl / vh});
}

/// Schlick's Fresnel F₀ + (1 − F₀)(1 − V·H)⁵.
template <std::floating_point T>
constexpr T fresnel_schlick(T vh, T f0) noexcept {
  const T m = T(1) - vh;
  const T m2 = m * m;
  return f0 + (T(1) - f0) * m2 * m2 * m;
}

/// Unpolarized dielectric Fresnel (Cook & Torrance 1982, eq. 8) with η from F₀:
/// η = (1 + √F₀)/(1 − √F₀). F₀ = 1 (η → ∞) is the perfect mirror, F ≡ 1.
template <std::floating_point T>
T fresnel_dielectric(T vh, T f0) noexcept {
  if (f0 >= T(1)) return T(1);
  const T r = std::sqrt(f0);
  const T eta = (T(1) + r) / (T(1) - r);
  const T c = vh;
  const T g = std::sqrt(eta * eta + c * c - T(1));
  const T a = (g - c) / (g + c);
  const T b = (c * (g + c) - T(1)) / (c * (g - c) + T(1));
  return T(0.5) * a * a * (T(1) + b * b);
}

}  // namespace specula::microfacet
