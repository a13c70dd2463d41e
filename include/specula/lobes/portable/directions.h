// Directions for importance sampling (docs/sampling.md), on any 3-vector type V with members x, y,
// z and construction V{x, y, z}: a frame about an axis, the mirror direction, cosine-weighted
// directions, the angle between two directions as y = −ln cos, and GGX's visible normals. Needs
// <cmath> alone: the library's sampler and frames (brdf/directions.h, src/sampling/sampler.cpp)
// compile this file, and `specula export --format cpp` embeds its text in every exported header
// that samples, so that the exported sampler and specula's are one source.
#ifndef SPECULA_LOBES_PORTABLE_DIRECTIONS_H
#define SPECULA_LOBES_PORTABLE_DIRECTIONS_H
#include <cmath>

namespace specula::radial {

template <class V>
double dot3(const V& a, const V& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class V>
V cross3(const V& a, const V& b) {
  return V{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class V>
V scaled3(const V& a, double s) {
  return V{a.x * s, a.y * s, a.z * s};
}
template <class V>
V unit3(const V& a) {
  return scaled3(a, 1 / std::sqrt(dot3(a, a)));
}

/// An orthonormal frame (t, b, w) around the unit vector w.
template <class V>
struct Frame {
  V t, b, w;

  explicit Frame(const V& axis) : w(axis) {
    const V helper = std::abs(w.x) < 0.9 ? V{1, 0, 0} : V{0, 1, 0};
    t = unit3(cross3(helper, w));
    b = cross3(w, t);
  }
  /// The direction at polar angle (cos θ, sin θ) from w and azimuth φ.
  V to_world(double cos_theta, double sin_theta, double phi) const {
    const V along_t = scaled3(t, sin_theta * std::cos(phi)), along_b = scaled3(b, sin_theta * std::sin(phi));
    const V along_w = scaled3(w, cos_theta);
    return V{along_t.x + along_b.x + along_w.x, along_t.y + along_b.y + along_w.y, along_t.z + along_b.z + along_w.z};
  }
};

/// 2(ω_i·H)H − ω_i: ω_i mirrored about H.
template <class V>
V mirror(const V& wi, const V& h) {
  const V twice = scaled3(h, 2 * dot3(wi, h));
  return V{twice.x - wi.x, twice.y - wi.y, twice.z - wi.z};
}

/// A cosine-weighted direction about +z from two uniform numbers.
template <class V>
V cosine_direction(double u1, double u2) {
  const double r = std::sqrt(u1), phi = 2 * 3.141592653589793 * u2, z2 = 1 - u1;
  return V{r * std::cos(phi), r * std::sin(phi), std::sqrt(z2 > 0 ? z2 : 0.0)};
}

/// y = −ln cos of the angle between the unit vectors a and b, from the sine near 0° (exact for
/// small angles), from the cosine beyond 60°; +∞ at or beyond 90°.
template <class V>
double log_cos_between(const V& a, const V& b) {
  const double c = dot3(a, b);
  if (!(c > 0)) return HUGE_VAL;
  if (c < 0.5) return -std::log(c);
  const V s = cross3(a, b);
  return -0.5 * std::log1p(-dot3(s, s));
}

/// GGX's visible normal H seen from ω_i, isotropic (Heitz 2018, "Sampling the GGX Distribution of
/// Visible Normals", JCGT 7(4)).
template <class V>
V ggx_visible_normal(double alpha, const V& wi, double u1, double u2) {
  const V vh = unit3(V{alpha * wi.x, alpha * wi.y, wi.z});
  const double len2 = vh.x * vh.x + vh.y * vh.y;
  const V t1 = len2 > 0 ? scaled3(V{-vh.y, vh.x, 0}, 1 / std::sqrt(len2)) : V{1, 0, 0};
  const V t2 = cross3(vh, t1);
  const double r = std::sqrt(u1), phi = 2 * 3.141592653589793 * u2;
  const double p1 = r * std::cos(phi), s = 0.5 * (1 + vh.z);
  const double rest1 = 1 - p1 * p1;
  const double p2 = (1 - s) * std::sqrt(rest1 > 0 ? rest1 : 0.0) + s * r * std::sin(phi);
  const double rest2 = 1 - p1 * p1 - p2 * p2;
  const V a = scaled3(t1, p1), b = scaled3(t2, p2), c = scaled3(vh, std::sqrt(rest2 > 0 ? rest2 : 0.0));
  const V nh{a.x + b.x + c.x, a.y + b.y + c.y, a.z + b.z + c.z};
  return unit3(V{alpha * nh.x, alpha * nh.y, nh.z > 0 ? nh.z : 0.0});
}

/// The density of ω_o = mirror(ω_i, H) for H drawn by ggx_visible_normal, per solid angle of ω_o:
/// D_ωi(H)/(4 ω_i·H) = G₁(ω_i) D(H)/(4 cos θ_i), Λ(ω_i) = (√(1 + α² tan²θ_i) − 1)/2.
template <class V>
double ggx_visible_pdf(double alpha, const V& wi, const V& h) {
  if (!(h.z > 0) || !(dot3(wi, h) > 0)) return 0;
  const double a2 = alpha * alpha, sin2 = h.x * h.x + h.y * h.y, q = h.z * h.z * a2 + sin2;
  const double d = a2 / (3.141592653589793 * q * q);
  const double c2 = wi.z * wi.z, lambda = (std::sqrt(1 + a2 * ((1 - c2) / c2)) - 1) / 2;
  return 1 / (1 + lambda) * d / (4 * wi.z);
}

}  // namespace specula::radial
#endif  // SPECULA_LOBES_PORTABLE_DIRECTIONS_H
