#pragma once
// F = c^n: Phong's lobe (Phong 1975), Blinn's when c = N·H (docs/math.md §2 `phong`).
#include "specula/lobes/lobe.h"

namespace specula::lobes {

template <std::floating_point T = double>
struct Power {
  T n = T(20);  ///< exponent, n > 0

  /// Max error: 2 ulp relative (float and double) for c ∈ [0, 1], n ∈ (0, 1e9] (std::pow).
  static constexpr ScalarErrorBound kMaxError{.ulps = 2};
  T operator()(T c) const noexcept { return std::pow(clamp_cos(c), n); }
  T at_log_cos(T u) const noexcept { return std::exp(-n * u); }
  T half_max_log_cos() const noexcept { return std::numbers::ln2_v<T> / n; }
  T support_log_cos() const noexcept { return kInfinity<T>; }
  /// The same lobe in lane type U.
  template <std::floating_point U>
  constexpr Power<U> as() const noexcept { return {U(n)}; }
};

}  // namespace specula::lobes
