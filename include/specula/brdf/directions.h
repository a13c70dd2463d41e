#pragma once
// Directions of docs/math.md §1: R = 2(N·L)N − L, H = (L + V)/|L + V|, and unit vectors from angles.
#include <utility>

#include "specula/brdf/vec3.h"
#include "specula/lobes/portable/directions.h"

namespace specula {

/// Mirror of L about N.
template <std::floating_point T>
constexpr Vec3T<T> reflect(const Vec3T<T>& l, const Vec3T<T>& n) noexcept {
  return n * (T(2) * dot(n, l)) - l;
}

/// Unit half vector of L and V.
template <std::floating_point T>
Vec3T<T> half_vector(const Vec3T<T>& l, const Vec3T<T>& v) noexcept {
  return normalized(l + v);
}

/// Unit vector at polar angle theta from +z and azimuth phi from +x (radians).
template <std::floating_point T>
Vec3T<T> from_spherical(T theta, T phi) noexcept {
  const T s = std::sin(theta);
  return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}

/// L and V of Rusinkiewicz's half/difference angles (1998, "A New Change of Variables for
/// Efficient BRDF Representation"), isotropic (φ_h = 0): H at polar angle θ_h in the xz-plane, L at
/// (θ_d, φ_d) about H as its pole (H's frame: z along H, y the surface's y), V = 2(L·H)H − L.
template <std::floating_point T>
std::pair<Vec3T<T>, Vec3T<T>> from_half_difference(T theta_h, T theta_d, T phi_d) noexcept {
  const Vec3T<T> d = from_spherical(theta_d, phi_d);
  const T c = std::cos(theta_h), s = std::sin(theta_h);
  const Vec3T<T> l{d.x * c + d.z * s, d.y, d.z * c - d.x * s};  // d rotated by θ_h about y
  return {l, reflect(l, Vec3T<T>{s, T(0), c})};
}

/// An orthonormal frame (t, b, w) around the unit vector w, and to_world(cos θ, sin θ, φ): the one
/// the sampler's exported copy embeds (lobes/portable/directions.h).
using Frame = radial::Frame<Vec3>;

template <std::floating_point T>
constexpr T radians(T degrees) noexcept {
  return degrees * (std::numbers::pi_v<T> / T(180));
}

}  // namespace specula
