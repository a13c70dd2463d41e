// The visible normals of a Smith microsurface, from any direction (microsurface.h).
#include "microsurface.h"

#include <algorithm>

namespace specula::walk::detail {

namespace {

constexpr double kPi = std::numbers::pi;

// GGX, stretched to α = 1 where the microsurface is a hemisphere: the visible normals of ω are
// ω + c, c uniform on the spherical cap z > −ω_z (Dupuy & Benyoub 2023, "Sampling Visible GGX
// Normals with Spherical Caps"). The cap keeps the normals above the horizon, which also holds
// for ω below it, where the cap is the part above |ω_z|.
Vec3 ggx_visible_normal(double alpha, const Vec3& w, double u1, double u2) noexcept {
  const Vec3 ws = normalized(Vec3{alpha * w.x, alpha * w.y, w.z});
  const double phi = 2 * kPi * u1;
  const double z = (1 - u2) * (1 + ws.z) - ws.z;
  const double r = std::sqrt(std::clamp(1 - z * z, 0.0, 1.0));
  const Vec3 h = Vec3{r * std::cos(phi), r * std::sin(phi), z} + ws;
  return normalized(Vec3{alpha * h.x, alpha * h.y, std::max(h.z, 0.0)});
}

// The s where 1 − (1 + s)e^(−s) = u (the gamma distribution of shape 2), by Newton's method
// in a bracket.
double gamma2_quantile(double u) noexcept {
  double lo = 0, hi = 100, s = 1.7;
  for (int i = 0; i < 100; ++i) {
    const double g = -std::expm1(-s) - s * std::exp(-s) - u;
    (g < 0 ? lo : hi) = s;
    double next = s * std::exp(-s) > 0 ? s - g / (s * std::exp(-s)) : (lo + hi) / 2;
    if (!(next > lo && next < hi)) next = (lo + hi) / 2;
    if (std::abs(next - s) < 1e-13 * (1 + s)) return next;
    s = next;
  }
  return s;
}

// An approximate erf⁻¹ (Giles 2010, "Approximating the erfinv function", single precision): the
// first guess of the Newton iteration below, which makes it exact.
double erfinv_guess(double x) noexcept {
  double w = -std::log((1 - x) * (1 + x)), p;
  if (w < 5) {
    w -= 2.5;
    p = 2.81022636e-08;
    for (double c : {3.43273939e-07, -3.5233877e-06, -4.39150654e-06, 0.00021858087, -0.00125372503, -0.00417768164,
                     0.246640727, 1.50140941})
      p = c + p * w;
  } else {
    w = std::sqrt(w) - 3;
    p = -0.000200214257;
    for (double c : {0.000100950558, 0.00134934322, -0.00367342844, 0.00573950773, -0.0076224613, 0.00943887047,
                     1.00167406, 2.83297682})
      p = c + p * w;
  }
  return p * x;
}

// Beckmann at α = 1, in slope space with ω in the xz-plane at θ from the zenith: the visible
// slopes' x has the density ∝ (cos θ − x sin θ) e^(−x²) on x < cot θ, whose unnormalized CDF is
// cdf(x) = cos θ · erfc(−x)/2 + sin θ · e^(−x²)/(2√π) (Heitz & d'Eon 2014, "Importance Sampling
// Microfacet-Based BSDFs using the Distribution of Visible Normals", §4); y is independent,
// normal with variance ½ (its quantile). x solves cdf(x) = u·cdf(cot θ) by Newton's method kept in a bracket,
// from Jakob's fit of the quantile in the erf domain (Mitsuba 0.6, "An Improved Visible Normal
// Sampling Routine for the Beckmann Distribution", 2014) where θ ≤ π/2.
double beckmann_visible_slope_x(double cos_t, double sin_t, double u) noexcept {
  const auto cdf = [&](double x) {
    return cos_t * std::erfc(-x) / 2 + sin_t * std::exp(-x * x) / (2 * std::sqrt(kPi));
  };
  const double top = sin_t > 0 ? cos_t / sin_t : INFINITY;
  if (top < -20) {
    // Far below the horizon, where cdf underflows: the density is ≈ (cot θ − x) e^(2 x cot θ)
    // below cot θ, so s = 2|cot θ|(cot θ − x) has the gamma(2) distribution, CDF 1 − (1 + s)e^(−s).
    // The neglected factor e^(−(cot θ − x)²) is above 0.99 but with probability 1e-33, and a
    // walk meets a facet from so far below with probability under e^(−400) (such a ray leaves).
    return top - gamma2_quantile(u) / (2 * -top);
  }
  double hi = std::min(top, 8.0), lo = std::min(top, 0.0) - 8;
  const double target = u * cdf(hi);
  double x = (lo + hi) / 2;
  if (cos_t > 0) {
    const double theta = std::atan2(sin_t, cos_t), c = std::erf(hi);
    const double fit = 1 + theta * (-0.876 + theta * (0.4265 - 0.0594 * theta));
    const double guess = erfinv_guess(std::clamp(c - (1 + c) * std::pow(1 - u, fit), -1 + 1e-15, 1 - 1e-15));
    if (guess > lo && guess < hi) x = guess;
  }
  for (int i = 0; i < 100; ++i) {
    const double g = cdf(x) - target;
    (g < 0 ? lo : hi) = x;
    const double slope = (cos_t - x * sin_t) * std::exp(-x * x) / std::sqrt(kPi);
    double next = slope > 0 ? x - g / slope : (lo + hi) / 2;
    if (!(next > lo && next < hi)) next = (lo + hi) / 2;
    if (std::abs(next - x) < 1e-12 * (1 + std::abs(x))) return next;
    x = next;
  }
  return x;
}

// The normal deviate of variance ½ at the quantile u: erf⁻¹(2u − 1), Giles' guess polished by
// one Newton step (its 1e-8 becomes rounding).
double half_normal_quantile(double u) noexcept {
  const double b = std::clamp(2 * u - 1, -1 + 1e-16, 1 - 1e-16);
  const double y = erfinv_guess(b);
  return y - (std::erf(y) - b) / (2 / std::sqrt(kPi) * std::exp(-y * y));
}

Vec3 beckmann_visible_normal(double alpha, const Vec3& w, double u1, double u2) noexcept {
  const Vec3 ws = normalized(Vec3{alpha * w.x, alpha * w.y, w.z});
  const double sin_t = std::sqrt(std::max(0.0, ws.x * ws.x + ws.y * ws.y));
  const double cos_phi = sin_t > 0 ? ws.x / sin_t : 1, sin_phi = sin_t > 0 ? ws.y / sin_t : 0;
  const double x = beckmann_visible_slope_x(ws.z, sin_t, u1);
  const double y = half_normal_quantile(u2);
  const double sx = alpha * (cos_phi * x - sin_phi * y), sy = alpha * (sin_phi * x + cos_phi * y);
  return normalized(Vec3{-sx, -sy, 1});
}

}  // namespace

Vec3 sample_visible_normal(const Microsurface& s, const Vec3& w, double u1, double u2) noexcept {
  return s.distribution == Distribution::ggx ? ggx_visible_normal(s.alpha, w, u1, u2)
                                             : beckmann_visible_normal(s.alpha, w, u1, u2);
}

}  // namespace specula::walk::detail
