// The SIMD batch lobes against the scalar double lobes, held to exactly the bounds that
// each family states (include/specula/families/<family>.h; simd::error_bound), on every instruction set this CPU runs:
// dense and random cosines, cosines dense in t = −n log₂ c (the log lobe's own variable, docs/math.md
// §3) and in the angle (Gauss), powers of two down to the subnormals, and the edge cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "simd/probe_cosines.h"
#include "simd/target_label.h"
#include "specula/families/families.h"
#include "specula/simd/lobes.h"
#include "specula/simd/targets.h"

namespace specula::simd {
namespace {

/// The built-in lobe families' kernels, in the order of their definitions (families/families.h).
const std::vector<Family> kFamilies = [] {
  std::vector<Family> all;
  for (std::size_t i = 0; i < families::kLobeFamilyCount; ++i) all.push_back(families::kFamilies[i]->simd);
  return all;
}();
constexpr Tier kTiers[] = {Tier::exact, Tier::fast};
// n across the valid range, with the log kernels' switch at n = 6 on both sides.
constexpr double kExponents[] = {1e-3, 0.1, 1, 2, 5, 5.999, 6, 20, 100, 1000, 1e4, 1e6, 1e9};

std::string_view family_name(Family family) {
  return family == Family::formula ? "formula" : families::lobe_family(family).name;
}

/// The scalar double lobe the batch is held to: its family's (families/<family>.h), or a user's
/// formula (tests/catalogue/).
lobes::Lobe scalar_lobe(const LobeSpec& lobe) {
  if (lobe.family == Family::formula) return *lobe.formula;
  const double params[] = {lobe.n, lobe.s};
  return families::lobe_family(lobe.family).make_lobe(std::span<const double>(params));
}

struct Check {
  std::size_t failures = 0;
  double worst_ratio = 0;  ///< the largest |F̃ − F| / allowed
  std::string worst;
};

/// Every value of `got` against the scalar double lobe, within error_bound<T>.
template <class T>
Check check_batch(const LobeSpec& lobe, Tier tier, const std::vector<T>& c, const std::vector<T>& got) {
  const ErrorBound bound = error_bound<T>(lobe.family, tier);
  const lobes::Lobe scalar = scalar_lobe(lobe);
  Check check;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double f = lobes::eval(scalar, double(c[i]));
    if (std::isnan(f) || std::isnan(got[i])) {
      if (std::isnan(f) != std::isnan(got[i])) ++check.failures;
      continue;
    }
    const double error = std::abs(double(got[i]) - f), allowed = bound.allowed(f, f > 0 ? std::log(f) : 0);
    if (error > allowed) ++check.failures;
    const double ratio = allowed > 0 ? error / allowed : (error > 0 ? INFINITY : 0);
    if (ratio > check.worst_ratio) {
      check.worst_ratio = ratio;
      check.worst = fmt::format("c = {:.9g}: got {:.17g}, reference {:.17g}, error {:.3g}, allowed {:.3g}",
                                double(c[i]), double(got[i]), f, error, allowed);
    }
  }
  return check;
}

template <class T>
void expect_within_bounds(std::size_t dense) {
  for (const Family family : kFamilies)
    for (const Tier tier : kTiers)
      for (const double n : kExponents) {
        const LobeSpec lobe{family, double(T(n)), double(T(1.25))};
        const std::vector<T> c = probe_cosines<T>(lobe.n, dense);
        std::vector<T> got(c.size());
        eval_batch(lobe, tier, std::span<const T>(c), std::span<T>(got));
        const Check check = check_batch(lobe, tier, c, got);
        EXPECT_EQ(check.failures, 0u) << current_target().name << " " << family_name(family) << " "
                                      << to_string(tier) << " n = " << n << ", worst " << check.worst;
      }
}

class EveryTarget : public ::testing::TestWithParam<std::int64_t> {
 protected:
  void SetUp() override { scope_.emplace(GetParam()); }
  void TearDown() override { scope_.reset(); }

 private:
  std::optional<ScopedTarget> scope_;
};

TEST_P(EveryTarget, FloatWithinStatedBounds) { expect_within_bounds<float>(4000); }

TEST_P(EveryTarget, DoubleWithinStatedBounds) { expect_within_bounds<double>(4000); }

TEST_P(EveryTarget, NanInNanOutExceptGauss) {
  const std::vector<double> c{NAN, 0.5, -NAN};
  for (const Family family : kFamilies)
    for (const Tier tier : kTiers) {
      std::vector<double> got(c.size());
      eval_batch(LobeSpec{family, 20}, tier, std::span<const double>(c), std::span<double>(got));
      std::vector<float> cf(c.begin(), c.end()), gotf(c.size());
      eval_batch(LobeSpec{family, 20}, tier, std::span<const float>(cf), std::span<float>(gotf));
      for (const std::size_t i : {std::size_t{0}, std::size_t{2}}) {
        const bool nan = family != Family::gauss;  // the scalar Gauss lobe tests c > 0: NaN gives 0
        EXPECT_EQ(std::isnan(got[i]), nan) << family_name(family) << " " << to_string(tier);
        EXPECT_EQ(std::isnan(gotf[i]), nan) << family_name(family) << " " << to_string(tier) << " float";
        if (!nan) {
          EXPECT_EQ(got[i], 0.0);
        }
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Simd, EveryTarget, ::testing::ValuesIn(runnable_targets()), target_label);

TEST(SimdLobes, ArraysOfAnyLengthAndAlignment) {
  // Lengths around the vector widths and odd offsets: the loop's unrolled part, single vectors
  // and the padded tail must all give what one long batch gives.
  std::vector<float> c(300);
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = float(std::cos(1.5 * double(i) / double(c.size())));
  for (const Family family : kFamilies)
    for (const Tier tier : kTiers) {
      const LobeSpec lobe{family, 20};
      std::vector<float> whole(c.size());
      eval_batch(lobe, tier, std::span<const float>(c), std::span<float>(whole));
      for (const std::size_t offset : {0, 1, 3})
        for (const std::size_t length : {0, 1, 7, 15, 16, 17, 33, 63, 64, 65, 129}) {
          std::vector<float> part(length + 1, -7.0f);
          eval_batch(lobe, tier, std::span<const float>(c).subspan(offset, length), std::span<float>(part));
          for (std::size_t i = 0; i < length; ++i)
            EXPECT_EQ(part[i], whole[offset + i]) << family_name(family) << " length " << length << " i " << i;
          EXPECT_EQ(part[length], -7.0f) << "wrote past the end";
        }
    }
}

TEST(SimdLobes, OutputShorterThanInputIsFilledOnly) {
  const std::vector<double> c(10, 0.9);
  std::vector<double> out(4, -1);
  eval_batch(LobeSpec{Family::power, 2}, Tier::exact, std::span<const double>(c), std::span<double>(out).first(3));
  EXPECT_NEAR(out[2], 0.81, 1e-15);
  EXPECT_EQ(out[3], -1);
}

TEST(SimdLobes, RunTimeLobeAndStructsAgree) {
  const std::vector<double> c{0.99, 0.95, 0.9, 0.5};
  const lobes::Lobe lobe = lobes::SchlickModified<double>{30, 1.5};
  std::vector<double> a(c.size()), b(c.size());
  eval_batch(spec_of(lobe), Tier::exact, std::span<const double>(c), std::span<double>(a));
  eval_batch(lobes::SchlickModified<double>{30, 1.5}, Tier::exact, std::span<const double>(c), std::span<double>(b));
  EXPECT_EQ(a, b);
  EXPECT_EQ(spec_of(lobe).s, 1.5);
  for (std::size_t i = 0; i < c.size(); ++i) EXPECT_NEAR(a[i], lobes::eval(lobe, c[i]), 1e-15);
}

TEST(SimdLobes, TheCheckCatchesAnErrorJustAboveTheBound) {
  // The bound check itself can fail: values moved by 1.5× the allowed error are caught.
  for (const Family family : kFamilies)
    for (const Tier tier : kTiers) {
      const LobeSpec lobe{family, 20};
      const lobes::Lobe scalar = scalar_lobe(lobe);
      const std::vector<double> c{0.999, 0.99, 0.97, 0.95};
      std::vector<double> got(c.size());
      const ErrorBound bound = error_bound<double>(family, tier);
      for (std::size_t i = 0; i < c.size(); ++i) {
        const double f = lobes::eval(scalar, c[i]);
        got[i] = f + 1.5 * bound.allowed(f, std::log(f));
      }
      EXPECT_EQ(check_batch(lobe, tier, c, got).failures, c.size()) << family_name(family) << " " << to_string(tier);
    }
}

TEST(SimdLobes, FastTierMeetsItsShadingBoundWithRoom) {
  // The criterion for the fast tier, measured: ≤ 1e-4 relative where F ≥ 1e-3 of the peak.
  for (const Family family : kFamilies)
    for (const double n : {1.0, 20.0, 1000.0}) {
      const std::vector<float> c = probe_cosines<float>(n, 2000);
      std::vector<float> got(c.size());
      eval_batch(LobeSpec{family, n}, Tier::fast, std::span<const float>(c), std::span<float>(got));
      const lobes::Lobe scalar = scalar_lobe(LobeSpec{family, n});
      double worst = 0;
      for (std::size_t i = 0; i < c.size(); ++i) {
        const double f = lobes::eval(scalar, double(c[i]));
        if (f >= 1e-3) worst = std::max(worst, std::abs(got[i] - f) / f);
      }
      EXPECT_LE(worst, 1e-4) << family_name(family) << " n = " << n;
    }
}

}  // namespace
}  // namespace specula::simd
