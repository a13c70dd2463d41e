#pragma once
// A minimal 3-vector for directions; N, L (toward the light), V (toward the viewer).
#include <cmath>
#include <concepts>
#include <numbers>

namespace specula {

template <std::floating_point T>
struct Vec3T {
  T x = 0, y = 0, z = 0;

  constexpr Vec3T operator+(const Vec3T& o) const noexcept { return {x + o.x, y + o.y, z + o.z}; }
  constexpr Vec3T operator-(const Vec3T& o) const noexcept { return {x - o.x, y - o.y, z - o.z}; }
  constexpr Vec3T operator*(T s) const noexcept { return {x * s, y * s, z * s}; }
  constexpr Vec3T operator-() const noexcept { return {-x, -y, -z}; }
};

using Vec3 = Vec3T<double>;

template <std::floating_point T>
constexpr T dot(const Vec3T<T>& a, const Vec3T<T>& b) noexcept {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <std::floating_point T>
constexpr Vec3T<T> cross(const Vec3T<T>& a, const Vec3T<T>& b) noexcept {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

template <std::floating_point T>
T length(const Vec3T<T>& a) noexcept {
  return std::sqrt(dot(a, a));
}

template <std::floating_point T>
Vec3T<T> normalized(const Vec3T<T>& a) noexcept {
  return a * (T(1) / length(a));
}

}  // namespace specula
