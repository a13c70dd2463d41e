#pragma once
// Schlick's rational approximations of c^n (docs/math.md §2 `schlick`, `schlick-modified`).
#include "specula/lobes/lobe.h"

namespace specula::lobes {

/// F = c / (n − n c + c): Schlick 1994, "An inexpensive BRDF model for physically-based
/// rendering"; same value and slope as c^n at c = 1.
template <std::floating_point T = double>
struct Schlick {
  T n = T(20);  ///< n > 0

  /// Max error: 4 ulp relative for c ∈ [0, 1], n ∈ (0, 1e9].
  static constexpr ScalarErrorBound kMaxError{.ulps = 4};
  T operator()(T c) const noexcept {
    c = clamp_cos(c);
    return c / (n * (T(1) - c) + c);  // 1 − c is exact near 1
  }
  T at_log_cos(T u) const noexcept { return T(1) / (n * std::expm1(u) + T(1)); }
  T half_max_log_cos() const noexcept { return std::log1p(T(1) / n); }
  T support_log_cos() const noexcept { return kInfinity<T>; }
  /// The same lobe in lane type U.
  template <std::floating_point U>
  constexpr Schlick<U> as() const noexcept { return {U(n)}; }
};

/// F = (s c)² / (n − n c + s c)² (docs/math.md §2 `schlick-modified`, reconstructed: the paper's
/// "second degree" Schlick lobe). s = 1.25 in the paper.
template <std::floating_point T = double>
struct SchlickModified {
  T n = T(20);     ///< n > 0
  T s = T(1.25);   ///< s > 0

  /// Max error: 12 ulp relative for c ∈ [0, 1], n ∈ (0, 1e9], s ∈ (0, 1e3].
  static constexpr ScalarErrorBound kMaxError{.ulps = 12};
  T operator()(T c) const noexcept {
    c = clamp_cos(c);
    const T q = s * c / (n * (T(1) - c) + s * c);
    return q * q;
  }
  T at_log_cos(T u) const noexcept {
    const T q = s / (n * std::expm1(u) + s);
    return q * q;
  }
  T half_max_log_cos() const noexcept {
    return std::log1p(s * (std::numbers::sqrt2_v<T> - T(1)) / n);
  }
  T support_log_cos() const noexcept { return kInfinity<T>; }
  /// The same lobe in lane type U.
  template <std::floating_point U>
  constexpr SchlickModified<U> as() const noexcept { return {U(n), U(s)}; }
};

}  // namespace specula::lobes
