#pragma once
// What every lobe shares: the cosine convention and the two forms (docs/math.md §1 "Conventions").
//
// A lobe is F(c) of one cosine c ∈ [0, 1] with F(1) = 1. Every lobe family is a small struct
// holding its parameters, templated on float or double, with
//   T operator()(T c)           F(c); c ≤ 0 gives 0, c > 1 is clamped to 1 (round-off)
//   T at_log_cos(T u)           F at u = −ln c ≥ 0, exact for narrow lobes where 1 − c underflows
//   T half_max_log_cos()        the u where F falls to ½: the lobe's width, a scale for integrals
//   T support_log_cos()         the u beyond which F = 0 (+∞ if none)
//   L<U> as<U>()                the same lobe in lane type U
//   kMaxError                   its stated max error (ScalarErrorBound), which its test enforces
// Evaluation is header-only, allocation-free and noexcept: fit for a renderer's inner loop.
#include <algorithm>
#include <cmath>
#include <concepts>
#include <limits>
#include <numbers>
#include <optional>
#include <string_view>

#include "specula/exceptions.h"

namespace specula {

/// How a lobe becomes a BRDF f = k·F(c): `rv` uses c = R·V (Phong), `nh` uses c = N·H (Blinn).
enum class Form { rv, nh };

/// How many forms there are (`nh` is the last; names_complete below fails on one added after it).
inline constexpr std::size_t kFormCount = static_cast<std::size_t>(Form::nh) + 1;

/// "rv" or "nh": the one list of the forms' names, which parsing reads too ("" outside the enum).
constexpr const char* to_string(Form form) noexcept {
  switch (form) {
    case Form::rv: return "rv";
    case Form::nh: return "nh";
  }
  return "";
}
static_assert(names_complete<Form, kFormCount>([](Form f) { return to_string(f); }));

/// The form named `text` ("rv" or "nh"), if any.
constexpr std::optional<Form> form_named(std::string_view text) noexcept {
  return enum_named<Form, kFormCount>(text, [](Form f) { return to_string(f); });
}

}  // namespace specula

namespace specula::lobes {

/// c clamped to [0, 1]; NaN passes through.
template <std::floating_point T>
constexpr T clamp_cos(T c) noexcept {
  return c < T(0) ? T(0) : (c > T(1) ? T(1) : c);
}

template <std::floating_point T>
inline constexpr T kInfinity = std::numeric_limits<T>::infinity();

/// A scalar lobe's stated max error against the exact F, as data (each lobe's kMaxError, which its
/// test enforces): |F − F_exact| ≤ (ulps + ulps_per_n_theta2 · n θ²) · ε · F_exact + abs, with ε the
/// type's machine epsilon, θ = acos c, and abs = abs_double or abs_float by the type.
struct ScalarErrorBound {
  double ulps = 0;
  double ulps_per_n_theta2 = 0;  ///< growth where the exponent's rounding is amplified (Gauss)
  double abs_double = 0;
  double abs_float = 0;

  template <std::floating_point T>
  T allowed(T n, T c, T exact) const noexcept {
    T ulps_here = T(ulps);
    if (ulps_per_n_theta2 != 0) {
      const T theta = std::acos(clamp_cos(c));
      ulps_here += T(ulps_per_n_theta2) * n * theta * theta;
    }
    const T abs = std::is_same_v<T, float> ? T(abs_float) : T(abs_double);
    return ulps_here * std::numeric_limits<T>::epsilon() * exact + abs;
  }
};

}  // namespace specula::lobes
