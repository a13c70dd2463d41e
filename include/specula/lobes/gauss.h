#pragma once
// F = exp(−n θ²/2), θ = acos c: the Gaussian lobe matched to c^n at the peak, since
// ln cos θ ≈ −θ²/2 (docs/math.md §2 `gauss`; the paper's Gauss BRDF, used with c = N·H).
#include "specula/lobes/lobe.h"

namespace specula::lobes {

template <std::floating_point T = double>
struct Gauss {
  T n = T(20);  ///< n > 0

  /// Max error: (4 + 1.5 n θ²) ulp relative for c ∈ (0, 1], n ∈ (0, 1e9]: the exponent's rounding,
  /// amplified where F is already tiny. F = 0 at c ≤ 0.
  static constexpr ScalarErrorBound kMaxError{.ulps = 4, .ulps_per_n_theta2 = 1.5};
  T operator()(T c) const noexcept {
    const T theta = std::acos(clamp_cos(c));
    return c > T(0) ? std::exp(-n * theta * theta / T(2)) : T(0);
  }
  /// θ from u without cancellation: 1 − cos θ = 2 sin²(θ/2) = −expm1(−u).
  T at_log_cos(T u) const noexcept {
    const T theta = T(2) * std::asin(std::sqrt(-std::expm1(-u) / T(2)));
    return std::isinf(u) ? T(0) : std::exp(-n * theta * theta / T(2));
  }
  T half_max_log_cos() const noexcept {
    const T theta = std::sqrt(T(2) * std::numbers::ln2_v<T> / n);
    return theta < std::numbers::pi_v<T> / 2 ? -std::log(std::cos(theta)) : kInfinity<T>;
  }
  T support_log_cos() const noexcept { return kInfinity<T>; }
  /// The same lobe in lane type U.
  template <std::floating_point U>
  constexpr Gauss<U> as() const noexcept { return {U(n)}; }
};

}  // namespace specula::lobes
