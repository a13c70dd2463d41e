#pragma once
// The Smith microsurface of the random walk (walk.h): Λ, D, the distribution of visible normals
// for any direction (below the horizon too: a ray travelling up meets facets from below) and the
// heights, in the convention of Heitz et al. 2016 (§4, the uniform height distribution):
// u = C₁(h) ∈ (0, 1] stands for the height, 1 above the surface.
#include <cmath>
#include <numbers>

#include "specula/brdf/vec3.h"
#include "specula/walk/walk.h"

namespace specula::walk::detail {

/// Λ(ω) for a unit ω of either hemisphere: Λ ≥ 0 above, Λ(ω) = −1 − Λ(−ω) below (Heitz 2014,
/// §5: the convention that makes the height sampling one formula for both).
/// GGX: Λ = (−1 + √(1 + 1/a²))/2; Beckmann: Λ = (e^(−a²)/(a√π) − erfc a)/2; a = |cot θ|/α.
inline double lambda(const Microsurface& s, const Vec3& w) noexcept {
  const double sin2 = w.x * w.x + w.y * w.y;
  if (sin2 == 0) return w.z > 0 ? 0.0 : -1.0;
  const double a = std::abs(w.z) / (s.alpha * std::sqrt(sin2));
  double up;
  if (s.distribution == Distribution::ggx) {
    up = (std::sqrt(1 + 1 / (a * a)) - 1) / 2;
  } else {
    up = a == 0 ? INFINITY : (std::exp(-a * a) / (a * std::sqrt(std::numbers::pi)) - std::erfc(a)) / 2;
    up = std::max(up, 0.0);  // the cancellation's rounding where Λ is below 1e-17 of its terms
  }
  return w.z > 0 ? up : -1 - up;
}

/// D(m) for a unit m (0 below the horizon).
inline double ndf(const Microsurface& s, const Vec3& m) noexcept {
  if (m.z <= 0) return 0;
  const double a2 = s.alpha * s.alpha, sin2 = m.x * m.x + m.y * m.y, cos2 = m.z * m.z;
  if (s.distribution == Distribution::ggx) {
    const double q = a2 * cos2 + sin2;  // cos²θ (α² + tan²θ)
    return a2 / (std::numbers::pi * q * q);
  }
  return std::exp(-sin2 / (cos2 * a2)) / (std::numbers::pi * a2 * cos2 * cos2);
}

/// The projected area of the microsurface seen from ω, (1 + Λ(ω)) cos θ (positive both ways).
inline double projected_area(const Microsurface& s, const Vec3& w) noexcept {
  return (1 + lambda(s, w)) * w.z;
}

/// A normal of the visible normals' distribution D_ω(m) = ⟨ω·m⟩ D(m) / projected_area(ω), from
/// two uniform numbers (a continuous map of the unit square, which the walk's net stratifies).
Vec3 sample_visible_normal(const Microsurface& s, const Vec3& w, double u1, double u2) noexcept;

/// The conductor's phase function without its Fresnel, p(ω_i → ω_o) = D_ωi(ω_h) / (4 ω_i·ω_h)
/// = D(ω_h) / (4 projected_area(ω_i)), ω_h the normalized ω_i + ω_o (0 when below the horizon);
/// a density in ω_o that integrates to 1 over the sphere. `half` receives ω_h.
inline double phase_function(const Microsurface& s, const Vec3& wi, const Vec3& wo, Vec3& half) noexcept {
  const Vec3 h = wi + wo;
  const double norm = length(h);
  if (norm == 0) return 0;
  half = h * (1 / norm);
  if (half.z <= 0) return 0;
  return ndf(s, half) / (4 * projected_area(s, wi));
}

}  // namespace specula::walk::detail
