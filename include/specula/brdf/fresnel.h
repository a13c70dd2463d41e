#pragma once
// Fresnel reflectance of unpolarized light, F(c) with c = cos θ the cosine between the incident
// direction and the (micro)normal, c ∈ [0, 1] (docs/fresnel.md):
//   Schlick 1994, with F90 and the exponent free: F0 + (F90 − F0)(1 − c)^p;
//   Hoffman 2019's F82-tint (as Cycles' fresnel_f82tint): Schlick's F minus b·c(1 − c)⁶, b chosen so
//   that F at c = 1/7 (θ ≈ 82°) is Schlick's value times the tint, clamped to [0, 1];
//   the exact dielectric interface, η = n_transmitted / n_incident, either side (η < 1 from the
//   denser side, total internal reflection below the critical cosine √(1 − η²));
//   the exact conductor, complex index η + iκ.
// One channel each: a coloured Fresnel is three of them (Rgb below).
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <concepts>

namespace specula::fresnel {

/// Schlick: F0 + (F90 − F0)(1 − c)^p.
template <std::floating_point T>
T schlick(T c, T f0, T f90 = T(1), T p = T(5)) noexcept {
  const T m = std::clamp(T(1) - c, T(0), T(1));
  const T m2 = m * m;
  const T mp = p == T(5) ? m2 * m2 * m : std::pow(m, p);
  return f0 + (f90 - f0) * mp;
}

/// Hoffman's b of the F82-tint model: Schlick (p = 5, F90 = 1) at c = 1/7 times (1 − tint), over
/// c(1 − c)⁶ at c = 1/7 (the correction's maximum).
template <std::floating_point T>
constexpr T f82_tint_b(T f0, T tint) noexcept {
  const T s = T(6) / T(7), s5 = s * s * s * s * s;
  const T at_82 = f0 + (T(1) - f0) * s5;
  return at_82 * (T(1) - tint) / (s5 * s / T(7));
}

/// F82-tint's polynomial before its clamp, with its b (f82_tint_b): Schlick − b·c(1 − c)⁶.
template <std::floating_point T>
T f82_tint_unclamped(T c, T f0, T b) noexcept {
  const T m = std::clamp(T(1) - c, T(0), T(1));
  const T m5 = m * m * m * m * m;
  return f0 + (T(1) - f0) * m5 - b * c * m5 * m;
}

/// F82-tint: f82_tint_unclamped clamped to [0, 1].
template <std::floating_point T>
T f82_tint(T c, T f0, T b) noexcept {
  return std::clamp(f82_tint_unclamped(c, f0, b), T(0), T(1));
}

/// The exact dielectric Fresnel (Cook & Torrance 1982, eq. 8, from either side): with
/// g² = η² − 1 + c², F = ½ ((g − c)/(g + c))² (1 + ((c(g + c) − 1)/(c(g − c) + 1))²);
/// g² ≤ 0 is total internal reflection, F = 1.
template <std::floating_point T>
T dielectric(T c, T eta) noexcept {
  c = std::clamp(c, T(0), T(1));
  const T g2 = eta * eta - T(1) + c * c;
  if (g2 <= T(0)) return T(1);
  const T g = std::sqrt(g2);
  const T a = (g - c) / (g + c);
  const T b = (c * (g + c) - T(1)) / (c * (g - c) + T(1));
  return T(0.5) * a * a * (T(1) + b * b);
}

/// The exact conductor Fresnel, index η + iκ, from the complex amplitudes (Born & Wolf §13.2):
/// cos θ_t = √(1 − sin²θ / (η + iκ)²), r_s = (c − n cos θ_t)/(c + n cos θ_t),
/// r_p = (n c − cos θ_t)/(n c + cos θ_t), F = (|r_s|² + |r_p|²)/2. With κ = 0 it is dielectric().
template <std::floating_point T>
T conductor(T c, T eta, T kappa) noexcept {
  c = std::clamp(c, T(0), T(1));
  const std::complex<T> n(eta, kappa);
  const std::complex<T> cos_t = std::sqrt(T(1) - (T(1) - c * c) / (n * n));
  const std::complex<T> rs = (c - n * cos_t) / (c + n * cos_t);
  const std::complex<T> rp = (n * c - cos_t) / (n * c + cos_t);
  return std::min(T(1), (std::norm(rs) + std::norm(rp)) / T(2));
}

/// The kinds of Fresnel a model may carry. `one` is F ≡ 1 (the models' F0 = 1, energy tests).
enum class Kind { one, schlick, f82_tint, dielectric, conductor };

/// One channel's Fresnel: a kind and its parameters (the unused ones ignored).
struct Channel {
  Kind kind = Kind::one;
  double f0 = 1, f90 = 1, exponent = 5;  ///< schlick; f82_tint: f0
  double tint = 1;                       ///< f82_tint: F(1/7) over Schlick's
  double eta = 1.5, kappa = 0;           ///< dielectric: eta; conductor: eta + i kappa

  /// True for Schlick's F0 alone (F90 = 1, exponent 5): the Fresnel SIMD kernels and shaders
  /// take as one number.
  bool is_schlick_f0() const noexcept { return kind == Kind::schlick && f90 == 1 && exponent == 5; }

  /// True where F ≡ 1 at every angle: `one`, Schlick at F0 = F90 = 1, F82 at F0 = tint = 1.
  bool is_one() const noexcept {
    return kind == Kind::one || (kind == Kind::schlick && f0 == 1 && f90 == 1) ||
           (kind == Kind::f82_tint && f0 == 1 && tint == 1);
  }

  template <std::floating_point T>
  T operator()(T c) const noexcept {
    switch (kind) {
      case Kind::one: return T(1);
      case Kind::schlick: return schlick(c, T(f0), T(f90), T(exponent));
      case Kind::f82_tint: return f82_tint(c, T(f0), f82_tint_b(T(f0), T(tint)));
      case Kind::dielectric: return dielectric(c, T(eta));
      case Kind::conductor: return conductor(c, T(eta), T(kappa));
    }
    return T(1);
  }
};

/// A coloured Fresnel: one channel per R, G, B.
using Rgb = std::array<Channel, 3>;

/// F_avg = 2∫₀¹ F(μ) μ dμ in closed form where one exists: Schlick with any exponent,
/// F0 + (F90 − F0)·2/((p + 1)(p + 2)); F82-tint, F0 + (1 − F0)/21 − b/126, exact where the clamp
/// to [0, 1] is inactive (the caller checks; analysis/fresnel.h integrates any channel).
constexpr double schlick_average(double f0, double f90 = 1, double p = 5) noexcept {
  return f0 + (f90 - f0) * 2 / ((p + 1) * (p + 2));
}
constexpr double f82_tint_average_unclamped(double f0, double tint) noexcept {
  return f0 + (1 - f0) / 21 - f82_tint_b(f0, tint) / 126;
}

/// The Kulla–Conty 2017 fit of a dielectric's F_avg, (η − 1)/(4.08567 + 1.00071 η), η ≥ 1.
/// Its true error against the integral is in docs/fresnel.md and tests/analysis/fresnel_test.cpp.
constexpr double kulla_conty_dielectric_average(double eta) noexcept {
  return (eta - 1) / (4.08567 + 1.00071 * eta);
}

}  // namespace specula::fresnel
