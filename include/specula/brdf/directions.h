#pragma once
// Directions of docs/math.md §1: R = 2(N·L)N − L, H = (L + V)/|L + V|, and unit vectors from angles.
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

/// An orthonormal frame (t, b, w) around the unit vector w, and to_world(cos θ, sin θ, φ): the one
/// the sampler's exported copy embeds (lobes/portable/directions.h).
using Frame = radial::Frame<Vec3>;

template <std::floating_point T>
constexpr T radians(T degrees) noexcept {
  return degrees * (std::numbers::pi_v<T> / T(180));
}

}  // namespace specula
