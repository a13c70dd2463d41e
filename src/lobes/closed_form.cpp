#include "specula/lobes/closed_form.h"

#include <cmath>
#include <numbers>

#include "specula/lobes/portable/radial.h"

namespace specula::lobes {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLn2 = std::numbers::ln2;

/// ∫₀¹ c² (1 − m(1 − c))^(−1) dc = Σ_j m^j · 2/((j+1)(j+2)(j+3)), m = 1 − n, |m| ≤ ½.
double schlick_rv_integral_series(double m) noexcept {
  double sum = 0, power = 1;
  for (int j = 0; j < 64; ++j, power *= m) sum += power * 2.0 / ((j + 1.0) * (j + 2.0) * (j + 3.0));
  return sum;
}

/// g(a) = ∫₀³ (1 − ½ log₂(1 + s)) e^(−a s) ds, the log lobe's integral in t-space (docs/math.md §4):
/// Int(n) = (a/2) g(a). For a ≤ 1 from E₁(a) − E₁(4a) = ln 4 + D'(a), D'(a) = Σ_{k≥1}
/// (−1)^k (4^k − 1) a^k/(k·k!), so that g = −[expm1(a)/a + e^a (D'(a)/a)/ln 4] never subtracts
/// two numbers near 1/a.
double log_lobe_t_integral_series(double a) noexcept {
  double d_over_a = 0;
  double a_pow = 1, factorial = 1, four_pow = 1;  // a^(k−1), k!, 4^k
  for (int k = 1; k < 60; ++k) {
    factorial *= k;
    four_pow *= 4;
    const double term = (four_pow - 1) * a_pow / (k * factorial);
    d_over_a += (k % 2 == 1) ? -term : term;
    if (term < 1e-18 * std::abs(d_over_a)) break;
    a_pow *= a;
  }
  const double expm1_over_a = a == 0 ? 1 : std::expm1(a) / a;
  return -(expm1_over_a + std::exp(a) * d_over_a / (2 * kLn2));
}

}  // namespace

double schlick_rv(double n) noexcept {
  const double m = 1 - n;
  double integral;
  if (std::abs(m) <= 0.5) {
    integral = schlick_rv_integral_series(m);
  } else {
    const double d = n - 1;
    integral = n * n * std::log(n) / (d * d * d) - n / (d * d) - 1 / (2 * d);
  }
  return 1 / (2 * kPi * integral);
}

double log_rv(double n) noexcept {
  const double a = 2 * kLn2 / n;
  if (a <= 1) return 1 / (kPi * a * log_lobe_t_integral_series(a));
  const double integral = 0.5 - (radial::scaled_e1(a) - std::exp(-3 * a) * radial::scaled_e1(4 * a)) / (4 * kLn2);
  return 1 / (2 * kPi * integral);
}

}  // namespace specula::lobes
