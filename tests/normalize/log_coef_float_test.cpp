// normalize::log_rv_approx — the float coef(n) the emitted GLSL computes — against the double
// closed form log_rv (itself held to 1e-13 of mpmath in normalize_test), over n ∈ [1e-6, 1e30].
#include <gtest/gtest.h>

#include <cmath>

#include "specula/lobes/closed_form.h"
#include "specula/normalize/log_coef_float.h"

namespace specula::normalize {
namespace {

struct Worst {
  double error = 0;
  double at = 0;
};

template <class T>
Worst worst_relative_error(double log10_lo, double log10_hi, int points) {
  Worst worst;
  for (int i = 0; i <= points; ++i) {
    const T n = static_cast<T>(std::pow(10.0, log10_lo + (log10_hi - log10_lo) * i / points));
    const double exact = lobes::log_rv(static_cast<double>(n));
    const double error = std::abs(static_cast<double>(log_rv_approx<T>(n)) / exact - 1);
    if (error > worst.error) worst = {error, static_cast<double>(n)};
  }
  return worst;
}

TEST(LogCoefFloat, Within4e7RelativeInFloatForEveryN) {
  const Worst wide = worst_relative_error<float>(-6, 30, 400000);
  const Worst near_one = worst_relative_error<float>(-0.5, 0.5, 200000);
  EXPECT_LE(wide.error, 4e-7) << "at n = " << wide.at;
  EXPECT_LE(near_one.error, 4e-7) << "at n = " << near_one.at;
  RecordProperty("max_relative_error", std::to_string(std::max(wide.error, near_one.error)));
}

TEST(LogCoefFloat, SeriesAloneWithinTheirStatedFitError) {
  // In double the rounding is negligible: what remains is the truncation of each series.
  const Worst high = worst_relative_error<double>(0, 12, 100000);
  const Worst low = worst_relative_error<double>(-6, 0, 100000);
  EXPECT_LE(high.error, 1.01 * log_coef_chebyshev::kJFitError + 1e-15) << "at n = " << high.at;
  EXPECT_LE(low.error, 1.01 * log_coef_chebyshev::kKFitError + 1e-15) << "at n = " << low.at;
  EXPECT_LE(std::max(log_coef_chebyshev::kJFitError, log_coef_chebyshev::kKFitError), 1e-9);
}

TEST(LogCoefFloat, LimitsAndTheSplitAtOne) {
  EXPECT_NEAR(log_rv_approx<double>(1e-12), 1 / std::numbers::pi, 1e-9);  // a flat lobe: Lambert's 1/π
  const double below = log_rv_approx<double>(std::nextafter(1.0, 0.0)), above = log_rv_approx<double>(1.0);
  EXPECT_NEAR(below / above, 1, 2e-9);
  EXPECT_NEAR(log_rv_approx<double>(1000), 197.49861008019521, 197.5 * 1e-9);  // docs/math.md §4 check value
}

}  // namespace
}  // namespace specula::normalize
