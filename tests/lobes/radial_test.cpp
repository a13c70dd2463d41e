// include/specula/lobes/portable/radial.h: the <cmath>-only functions that the sampler, the log
// lobe's closed-form k and the C++ export share, each held to the max error its comment states,
// against a second method (Boost's E₁ in long double; Gauss-Kronrod quadrature in long double).
#include "specula/lobes/portable/radial.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/special_functions/expint.hpp>
#include <cmath>
#include <limits>

namespace specula::radial {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

long double scaled_e1_reference(long double x) { return std::exp(x) * boost::math::expint(1, x); }

/// The largest relative error of `e1` (scaled_e1 or a stand-in) over x ∈ [1, 700], in steps of 1 %.
template <class F>
double worst_scaled_e1_error(const F& e1) {
  double worst = 0;
  for (double x = 1; x <= 700; x *= 1.01) {
    const long double reference = scaled_e1_reference(x);
    worst = std::max(worst, double(std::abs((e1(x) - reference) / reference)));
  }
  return worst;
}

TEST(Radial, ScaledE1WithinItsStatedBound) {
  const double worst = worst_scaled_e1_error([](double x) { return scaled_e1(x); });
  std::printf("scaled_e1: max relative error %.3g ulp over [1, 700]\n", worst / kEps);
  EXPECT_LE(worst, 4 * kEps);
}

// Negative control: a scaled_e1 off by 8 ulp fails the same check.
TEST(Radial, ScaledE1CheckFailsEightUlpOff) {
  EXPECT_GT(worst_scaled_e1_error([](double x) { return scaled_e1(x) * (1 + 8 * kEps); }), 4 * kEps);
}

long double log_t_integral_reference(long double b, long double t) {
  auto f = [b](long double s) { return (1 - 0.5L * std::log1p(s) / std::log(2.0L)) * std::exp(-b * s); };
  return boost::math::quadrature::gauss_kronrod<long double, 61>::integrate(f, 0.0L, t, 12, 1e-19L);
}

TEST(Radial, LogTIntegralWithinItsStatedBound) {
  double worst = 0;
  for (double b = 1e-9; b <= 1e3; b *= 4) {
    const long double total = log_t_integral_reference(b, 3);
    for (double t : {1e-6, 0.01, 0.5, 1.0, 2.0, 2.999, 3.0}) {
      const long double reference = log_t_integral_reference(b, t);
      worst = std::max(worst, double(std::abs((log_t_integral(b, t) - reference) / total)));
    }
  }
  std::printf("log_t_integral: max error %.3g of G_b(3)\n", worst);
  EXPECT_LE(worst, 1e-14);
}

}  // namespace
}  // namespace specula::radial
