// Approximation error maxima against closed forms and a brute-force second method (docs/math.md §3).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "specula/analysis/error.h"
#include "specula/exceptions.h"

namespace specula::analysis {
namespace {

struct BruteForce {
  double max_abs = 0, argmax_c = 0, max_rel_epicenter = 0;
};

/// An independent second method: 2e6 samples uniform in c (no t-space, no refinement).
template <class A, class B>
BruteForce brute_force(const A& a, const B& ref, double zone) {
  BruteForce r;
  constexpr int kSamples = 2'000'000;
  for (int i = 0; i <= kSamples; ++i) {
    const double c = static_cast<double>(i) / kSamples;
    const double fa = a(c), fr = ref(c);
    if (std::abs(fa - fr) > r.max_abs) r.max_abs = std::abs(fa - fr), r.argmax_c = c;
    if (fr >= zone) r.max_rel_epicenter = std::max(r.max_rel_epicenter, std::abs(fa - fr) / fr);
  }
  return r;
}

TEST(ApproximationError, LogVsPhongIsOneEighthAtTEqualsThreeForEveryN) {
  for (const double n : {1.0, 2.0, 7.0, 20.0, 100.0, 1000.0, 1e5}) {
    const auto e = approximation_error(lobes::Log<>{n}, lobes::Power<>{n});
    EXPECT_NEAR(e.max_abs, 0.125, 1e-12) << n;
    EXPECT_NEAR(e.argmax_abs_deg, std::acos(std::exp2(-3 / n)) * 180 / std::numbers::pi, 1e-6) << n;
    EXPECT_EQ(e.max_rel_attenuation, 1) << n;  // F_log = 0 where c^n > 0
  }
}

TEST(ApproximationError, LogEpicenterErrorIsNIndependent) {
  // max over t ∈ [0, 1] of |1 − ½ log₂(1 + t) − 2^(−t)| / 2^(−t), by brute force in t.
  double expected = 0;
  for (int i = 0; i <= 1'000'000; ++i) {
    const double t = i / 1e6;
    expected = std::max(expected, std::abs(1 - 0.5 * std::log2(1 + t) - std::exp2(-t)) / std::exp2(-t));
  }
  EXPECT_NEAR(expected, 0.0029, 1e-4);  // docs/math.md §3: ≈ 0.29 %
  for (const double n : {1.0, 20.0, 1000.0})
    EXPECT_NEAR(approximation_error(lobes::Log<>{n}, lobes::Power<>{n}).max_rel_epicenter, expected, 1e-9) << n;
}

TEST(ApproximationError, SchlickAgreesWithBruteForce) {
  for (const double n : {2.0, 20.0, 100.0}) {
    const lobes::Schlick<> schlick{n};
    const lobes::Power<> power{n};
    const auto e = approximation_error(schlick, power);
    const auto b = brute_force(schlick, power, 0.5);
    EXPECT_GE(e.max_abs, b.max_abs) << n;  // the exact maximum is never below a sampled one
    EXPECT_NEAR(e.max_abs, b.max_abs, 1e-9) << n;
    EXPECT_NEAR(std::cos(e.argmax_abs_deg * std::numbers::pi / 180), b.argmax_c, 1e-5) << n;
    // Schlick's relative error grows towards the zone's edge, c^n = ½: its maximum is there.
    EXPECT_GE(e.max_rel_epicenter, b.max_rel_epicenter) << n;
    const double edge = std::exp2(-1 / n);
    EXPECT_NEAR(e.max_rel_epicenter, std::abs(schlick(edge) - 0.5) / 0.5, 1e-12) << n;
  }
  // The paper's Fig. 4 values (docs/math.md §3, the issue): about 0.09 at n = 2 and 0.19 at n = 20.
  EXPECT_NEAR(approximation_error(lobes::Schlick<>{2}, lobes::Power<>{2}).max_abs, 0.09, 0.005);
  EXPECT_NEAR(approximation_error(lobes::Schlick<>{20}, lobes::Power<>{20}).max_abs, 0.19, 0.005);
  // And Fig. 3: ≈ 9 % at n = 2, ≈ 18 % for large n.
  EXPECT_NEAR(approximation_error(lobes::Schlick<>{2}, lobes::Power<>{2}).max_rel_epicenter, 0.09, 0.01);
  EXPECT_NEAR(approximation_error(lobes::Schlick<>{1000}, lobes::Power<>{1000}).max_rel_epicenter, 0.18, 0.01);
}

TEST(ApproximationError, IdenticalLobesHaveNoError) {
  const auto e = approximation_error(lobes::Gauss<>{50}, lobes::Gauss<>{50});
  EXPECT_EQ(e.max_abs, 0);
  EXPECT_EQ(e.max_rel_epicenter, 0);
  EXPECT_EQ(e.max_rel_attenuation, 0);
}

TEST(ApproximationError, RefusesABadZone) {
  EXPECT_THROW(approximation_error(lobes::Log<>{1}, lobes::Power<>{1}, 0), InvalidArgument);
  EXPECT_THROW(approximation_error(lobes::Log<>{1}, lobes::Power<>{1}, 1), InvalidArgument);
}

}  // namespace
}  // namespace specula::analysis
