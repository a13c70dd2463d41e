// The adaptive quadrature under the albedo, E_avg and the normalizations (src/numeric/piecewise.h):
// what it spends on a short piece, on an integrand with rounding noise and on a negligible piece,
// which ran every interval to the depth limit before (issue 23), and on root-type ends; and the
// controls that it still refines a kink, a jump and O(1) noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "../../src/numeric/piecewise.h"

namespace specula::numeric {
namespace {

/// exp(x) with a deterministic relative perturbation of `amplitude` (as rounding would leave).
double noisy_exp(double x, double amplitude) {
  std::uint64_t bits = 0;
  const double scaled = x * 1e6;
  std::memcpy(&bits, &scaled, sizeof bits);
  bits ^= bits >> 33, bits *= 0xff51afd7ed558ccdULL, bits ^= bits >> 33;
  const double unit = double(bits >> 11) * 0x1p-53 - 0.5;
  return std::exp(x) * (1 + amplitude * unit);
}

// Boost's error test shrank with a piece's length: a 1e-3 piece of exp ran to depth 15 (10⁶
// evaluations) although K31 is exact there.
TEST(Quadrature, AShortSmoothPieceTakesOneRule) {
  const auto f = [](double x) { return std::exp(x); };
  const Estimate e = integrate_pieces(f, 0, 1, 1, {1e-3});
  EXPECT_NEAR(e.value, std::expm1(1.0), 1e-15);
  EXPECT_EQ(e.evaluations, 2 * 31u);
}

TEST(Quadrature, NoiseBelowTheToleranceIsNotChased) {
  const auto f = [](double x) { return noisy_exp(x, 1e-11); };
  const Estimate e = integrate_pieces(f, 0, 1, 1, {}, 1e-13);
  EXPECT_NEAR(e.value, std::expm1(1.0), 1e-11);
  EXPECT_LE(e.evaluations, 31u * 16);  // before: 31 × 2^16
}

// The controls: a kink nobody located, and a jump, are refined as far as the depth allows
// (bisection leaves one half clean), and O(1) noise is not taken for rounding (the ceiling).
TEST(Quadrature, AnUnlocatedKinkOrJumpIsStillRefined) {
  const Estimate kink = integrate_pieces([](double x) { return std::abs(x - 0.3); }, 0, 1, 1, {}, 1e-12);
  EXPECT_NEAR(kink.value, (0.09 + 0.49) / 2, 1e-12);
  EXPECT_GT(kink.evaluations, 31u * 8);
  const Estimate jump = integrate_pieces([](double x) { return x < 0.3 ? 1.0 : 2.0; }, 0, 1, 1, {}, 1e-9);
  EXPECT_NEAR(jump.value, 1.7, 1e-6);  // the step within 2^-15 of 0.3
  const Estimate rough = integrate_pieces([](double x) { return noisy_exp(x, 1); }, 0, 1, 1, {}, 1e-13, 6);
  EXPECT_EQ(rough.evaluations, 31u * (2 * 64 - 1));  // every interval to depth 6
}

// Root-type ends (the albedo's outer integral where the horizon or a kink enters): the sin² map
// makes them smooth; the control, the plain pieces, refine toward both ends.
TEST(Quadrature, SmoothedEndsTakeRootSingularitiesInOneRule) {
  const auto f = [](double x) { return std::sqrt(x) + std::sqrt(1 - x); };
  const Estimate smoothed = integrate_pieces(f, 0, 1, 1, {}, 1e-12, 15, Ends::smoothed);
  EXPECT_NEAR(smoothed.value, 4.0 / 3, 1e-14);
  EXPECT_EQ(smoothed.evaluations, 31u);
  const Estimate plain = integrate_pieces(f, 0, 1, 1, {}, 1e-12);
  EXPECT_NEAR(plain.value, 4.0 / 3, 1e-11);
  EXPECT_GT(plain.evaluations, 31u * 20);
}

// A piece that weighs nothing next to the others needs no relative accuracy of its own.
TEST(Quadrature, ANegligiblePieceIsNotRefinedForItsOwnSake) {
  const auto f = [](double x) { return x < 1 ? std::exp(x) : 1e-30 * noisy_exp(x, 1e-2); };
  const Estimate e = integrate_pieces(f, 0, 2, 2, {1.0}, 1e-12);
  EXPECT_NEAR(e.value, std::expm1(1.0), 1e-12);
  EXPECT_EQ(e.evaluations, 2 * 31u);
}

// A non-finite integrand (a user's `1/(nl-nl)`, or values whose sum passes the largest double)
// stays non-finite in every half: before, each interval was bisected to max_depth, and an albedo
// (an integral of integrals) of `brdf: 1e308` ran for hours. The control: the same sum a factor
// below overflow is refined and finite.
TEST(Quadrature, ANonFiniteIntegrandIsNotBisected) {
  const auto infinite = [](double) { return std::numeric_limits<double>::infinity(); };
  const auto not_a_number = [](double x) { return std::sqrt(-x); };
  const auto huge = [](double x) { return x < 0.3 ? 1e308 : 1.7e308; };
  for (const auto& e : {integrate_pieces(infinite, 0, 1, 1), integrate_pieces(not_a_number, 0, 1, 1),
                        integrate_pieces(huge, 0, 1, 1)}) {
    EXPECT_FALSE(std::isfinite(e.value));
    EXPECT_EQ(e.evaluations, 31u);
  }
  const Estimate scaled = integrate_pieces([&](double x) { return huge(x) * 1e-10; }, 0, 1, 1, {}, 1e-9);
  EXPECT_NEAR(scaled.value, 1.49e298, 1e292);
  EXPECT_GT(scaled.evaluations, 31u * 8);
}

}  // namespace
}  // namespace specula::numeric
