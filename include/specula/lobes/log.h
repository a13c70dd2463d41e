#pragma once
// The paper's lobe: F_log = max(0, 1 − ½ log₂(1 − n log₂ c)) (Romanyuk et al. 2023, eq. for
// F_log; docs/math.md §2 `log`). Zero for c ≤ c₀ = 2^(−3/n). In t = −n log₂ c it is
// 1 − ½ log₂(1 + t) on t ∈ [0, 3], independent of n (docs/math.md §3).
#include "specula/lobes/lobe.h"

namespace specula::lobes {

template <std::floating_point T = double>
struct Log {
  T n = T(20);  ///< n > 0

  /// Max error: 8 ulp relative + 4e-16 absolute (double), 8 ulp + 2e-7 absolute (float), for
  /// c ∈ [0, 1], n ∈ [1e-3, 1e9]; the absolute part is where F cancels towards 0 near c₀.
  static constexpr ScalarErrorBound kMaxError{.ulps = 8, .abs_double = 4e-16, .abs_float = 2e-7};
  T operator()(T c) const noexcept {
    const T f = T(1) - T(0.5) * std::log2(T(1) - n * std::log2(clamp_cos(c)));
    return std::max(f, T(0));
  }
  T at_log_cos(T u) const noexcept {
    const T t = n * u / std::numbers::ln2_v<T>;
    return std::max(T(1) - T(0.5) * std::log1p(t) / std::numbers::ln2_v<T>, T(0));
  }
  T half_max_log_cos() const noexcept { return std::numbers::ln2_v<T> / n; }
  T support_log_cos() const noexcept { return T(3) * std::numbers::ln2_v<T> / n; }
  /// c₀ = 2^(−3/n), the cosine below which F = 0.
  T cutoff_cos() const noexcept { return std::exp2(T(-3) / n); }
  /// The same lobe in lane type U.
  template <std::floating_point U>
  constexpr Log<U> as() const noexcept { return {U(n)}; }
};

}  // namespace specula::lobes
