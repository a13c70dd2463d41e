// The adaptive integration under every quadrature (normalization, albedo, E_avg) checks the work
// limit inside one integral, every numeric::kEvaluationsPerCheck evaluations of the integrand
// (issue 23): an expensive or noisy integrand (a user's formula) may take 2^15 × 31 evaluations
// in one piece, and the deadline or Ctrl-C must not wait for them.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>

#include "../../src/numeric/piecewise.h"
#include "specula/interrupt/interrupt.h"

namespace specula::numeric {
namespace {

/// Noise the error control never accepts: every piece runs to its full depth.
double noise(double x) { return std::sin(1e9 * x); }

TEST(IntegralInterrupt, ACancelInsideOnePieceStopsItWithinOneCheck) {
  std::atomic<bool> cancel{false};
  std::size_t calls = 0;
  constexpr std::size_t kCancelAt = 1000;
  auto integrand = [&](double x) {
    if (++calls == kCancelAt) cancel = true;
    return noise(x);
  };
  const ScopedLimit limit(WorkLimit{std::chrono::steady_clock::time_point::max(), &cancel});
  EXPECT_THROW(integrate_pieces(integrand, 0, 1, 1), Interrupted);
  EXPECT_GE(calls, kCancelAt);
  EXPECT_LT(calls, kCancelAt + kEvaluationsPerCheck);
}

TEST(IntegralInterrupt, WithoutACancelTheSameIntegralRunsToTheEnd) {  // the control
  std::atomic<bool> cancel{false};
  std::size_t calls = 0;
  auto integrand = [&](double x) {
    ++calls;
    return noise(x);
  };
  const ScopedLimit limit(WorkLimit{std::chrono::steady_clock::time_point::max(), &cancel});
  const Estimate e = integrate_pieces(integrand, 0, 1, 1, {}, kDefaultTolerance, 10);
  EXPECT_TRUE(std::isfinite(e.value));
  EXPECT_GT(calls, 10 * kEvaluationsPerCheck);  // many checks passed
}

}  // namespace
}  // namespace specula::numeric
