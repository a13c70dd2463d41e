#pragma once
// The log lobe's exact normalization coef(n) (docs/math.md §4) for float shaders: two Chebyshev
// series fitted by scripts/make_log_coef_fit.py, evaluated in float by Clenshaw's recurrence.
// This is the arithmetic the emitted GLSL (glsl/glsl.h, specula_log_coef) performs, so the test of
// this function states the shader's error too.
#include <numbers>
#include <span>

#include "specula/normalize/log_coef_chebyshev.h"

namespace specula::normalize {

/// Σ c[k] T_k(t), t = 2x/high − 1, c[0] already halved (Clenshaw's recurrence, in T).
template <class T>
T chebyshev_series(std::span<const double> c, T high, T x) noexcept {
  const T t = T(2) * x / high - T(1);
  T b1 = 0, b2 = 0;
  for (std::size_t k = c.size() - 1; k >= 1; --k) {
    const T b0 = T(c[k]) + T(2) * t * b1 - b2;
    b2 = b1;
    b1 = b0;
  }
  return T(c[0]) + t * b1 - b2;
}

/// coef(n) = 1/(π a J(a)), a = 2 ln 2/n, from the series for J (n ≥ 1) or K = a J (n < 1).
/// Max error: 4e-7 relative in float for n ∈ (0, 1e30] (measured 3.0e-7 near n = 1.1; the test
/// holds 4e-7 on a dense grid). The series alone are within 1e-9 (kJFitError, kKFitError).
template <class T = float>
T log_rv_approx(T n) noexcept {
  namespace cheb = log_coef_chebyshev;
  constexpr double pi = std::numbers::pi, ln2 = std::numbers::ln2;
  if (n >= T(1))
    return n * T(1 / (2 * pi * ln2)) / chebyshev_series<T>(cheb::kJ, T(cheb::kJHigh), T(2 * ln2) / n);
  return T(1 / pi) / chebyshev_series<T>(cheb::kK, T(cheb::kKHigh), n * T(1 / (2 * ln2)));
}

}  // namespace specula::normalize
