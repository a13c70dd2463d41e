// Every lobe family against mpmath (tests/reference/lobes.csv), in double and in float, held to
// the error bounds their headers state; and the properties every lobe has (docs/math.md §1).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <variant>

#include "reference_table.h"
#include "specula/families/families.h"
#include "specula/lobes/lobes.h"

namespace specula::lobes {
namespace {

/// f(the lobe of tests/reference/lobes.csv's `family` at n, s): the one map from its names to types.
template <std::floating_point T, class F>
auto with_lobe(const std::string& family, T n, T s, F&& f) {
  if (family == "power") return f(Power<T>{n});
  if (family == "schlick") return f(Schlick<T>{n});
  if (family == "schlick-modified") return f(SchlickModified<T>{n, s});
  if (family == "gauss") return f(Gauss<T>{n});
  if (family == "log") return f(Log<T>{n});
  throw std::runtime_error("unknown lobe family " + family);
}

template <std::floating_point T>
T eval_family(const std::string& family, T n, T s, T c) {
  return with_lobe(family, n, s, [c](const auto& lobe) { return lobe(c); });
}

/// The bound the lobe's header states (its kMaxError).
template <std::floating_point T>
T stated_bound(const std::string& family, T n, T s, T c, T expected) {
  return with_lobe(family, n, s, [&](const auto& lobe) { return lobe.kMaxError.allowed(n, c, expected); });
}

struct Worst {
  double rel = 0;
  std::string where;
};

TEST(LobesReference, DoubleWithinStatedBounds) {
  const auto rows = testing::read_reference("lobes.csv");
  ASSERT_GT(rows.size(), 800u);
  std::map<std::string, Worst> worst;
  for (const auto& row : rows) {
    const std::string family = row.text("lobe");
    const double n = row.number("n"), s = row.number("s"), c = row.number("c");
    const double expected = row.number("value");
    const double got = eval_family(family, n, s, c);
    EXPECT_LE(std::abs(got - expected), stated_bound(family, n, s, c, expected))
        << family << " n=" << row.text("n") << " c=" << row.text("c") << " got " << got
        << " expected " << expected;
    if (expected > 1e-300) {
      const double rel = std::abs(got - expected) / expected;
      if (rel > worst[family].rel) worst[family] = {rel, "n=" + row.text("n") + " c=" + row.text("c")};
    }
  }
  for (const auto& [family, w] : worst)
    std::printf("%-17s max relative error %.3g ulp at %s\n", family.c_str(),
                w.rel / std::numeric_limits<double>::epsilon(), w.where.c_str());
}

// Float: the reference is the double path at the same float inputs (validated above), since the
// float rounding of c alone moves a narrow lobe far more than the evaluation does.
TEST(LobesReference, FloatWithinStatedBounds) {
  const auto rows = testing::read_reference("lobes.csv");
  for (const auto& row : rows) {
    const std::string family = row.text("lobe");
    const float n = static_cast<float>(row.number("n"));
    const float s = static_cast<float>(row.number("s"));
    const float c = static_cast<float>(row.number("c"));
    if (!(n > 0) || !std::isfinite(n)) continue;
    const double expected = eval_family<double>(family, n, s, c);
    const float got = eval_family(family, n, s, c);
    EXPECT_LE(std::abs(got - expected),
              stated_bound<float>(family, n, s, c, static_cast<float>(expected)) + 1e-37)
        << family << " n=" << n << " c=" << c << " got " << got << " expected " << expected;
  }
}

TEST(LobesReference, EveryFamilyAndTheCutOffAreCovered) {
  std::set<std::string> families;
  int just_above_cutoff = 0;
  for (const auto& row : testing::read_reference("lobes.csv")) {
    families.insert(row.text("lobe"));
    if (row.text("lobe") == "log") {
      const double c0 = std::exp2(-3 / row.number("n"));
      const double c = row.number("c");
      if (c > c0 && c < c0 * (1 + 1e-8)) ++just_above_cutoff;
    }
  }
  // Every built-in family: all of Lobe's but Formula, a user's lobe (tests/catalogue/).
  EXPECT_EQ(families.size(), std::variant_size_v<Lobe> - 1);
  EXPECT_GE(just_above_cutoff, 20);
}

TEST(LogLobe, ZeroAtAndBelowTheCutOffPositiveAbove) {
  for (const double n : {0.5, 1.0, 3.0, 20.0, 1e3, 1e6}) {
    const Log<> lobe{n};
    const double c0 = lobe.cutoff_cos();
    EXPECT_EQ(lobe(std::nextafter(c0, 0.0) * (1 - 1e-9)), 0.0) << n;
    EXPECT_GT(lobe(c0 * (1 + 1e-6)), 0.0) << n;
  }
}

TEST(LogLobe, IsNIndependentInTSpace) {
  // docs/math.md §3: with c = 2^(−t/n), F_log = 1 − ½ log₂(1 + t) whatever n is.
  for (const double t : {0.0, 0.25, 1.0, 2.0, 2.9})
    for (const double n : {1.0, 20.0, 1000.0})
      EXPECT_NEAR(Log<>{n}(std::exp2(-t / n)), 1 - 0.5 * std::log2(1 + t), 1e-12) << t << " " << n;
}

TEST(Lobes, AtLogCosAgreesWithEvaluationInC) {
  for (const double n : {0.01, 1.0, 20.0, 1e4})
    for (const double u : {0.0, 1e-6, 1e-3, 0.01, 0.1, 0.5, 2.0}) {
      const double c = std::exp(-u);
      for (const Lobe& lobe : {Lobe{Power<>{n}}, Lobe{Schlick<>{n}}, Lobe{SchlickModified<>{n, 1.25}},
                               Lobe{Gauss<>{n}}, Lobe{Log<>{n}}}) {
        const double in_c = eval(lobe, c);
        EXPECT_NEAR(at_log_cos(lobe, u), in_c, 1e-9 * (1 + in_c) + 1e-12 * n * u)
            << families::family_name(lobe) << " n=" << n << " u=" << u;
      }
    }
}

TEST(Lobes, BatchEqualsScalar) {
  const Lobe lobe = Log<>{20};
  std::vector<double> c, out(101);
  for (int i = 0; i <= 100; ++i) c.push_back(i / 100.0);
  eval_batch(lobe, std::span<const double>(c), std::span<double>(out));
  for (int i = 0; i <= 100; ++i) EXPECT_EQ(out[i], eval(lobe, c[i]));
}

// Properties (docs/math.md §1): F(1) = 1, 0 ≤ F ≤ 1, F = 0 for c ≤ 0, monotone in c.
rc::Gen<Lobe> any_lobe() {
  return rc::gen::apply(
      [](int family, double log10_n, double s) -> Lobe {
        const double n = std::pow(10.0, log10_n);
        switch (family) {
          case 0: return Power<>{n};
          case 1: return Schlick<>{n};
          case 2: return SchlickModified<>{n, s};
          case 3: return Gauss<>{n};
          default: return Log<>{n};
        }
      },
      rc::gen::inRange(0, 5), rc::gen::map(rc::gen::inRange(-3000, 9000), [](int k) { return k / 1000.0; }),
      rc::gen::map(rc::gen::inRange(1, 4000), [](int k) { return k / 1000.0; }));
}

rc::Gen<double> unit_interval() {
  return rc::gen::map(rc::gen::inRange<std::int64_t>(0, 1'000'000'001),
                      [](std::int64_t k) { return static_cast<double>(k) / 1e9; });
}

RC_GTEST_PROP(LobeProperties, PeakIsOne, ()) {
  const Lobe lobe = *any_lobe();
  RC_ASSERT(eval(lobe, 1.0) == 1.0);
  RC_ASSERT(eval(lobe, 1.0 + 1e-12) == 1.0);  // round-off above 1 is clamped
}

RC_GTEST_PROP(LobeProperties, BoundedAndZeroBelowTheHorizon, ()) {
  const Lobe lobe = *any_lobe();
  const double c = *unit_interval();
  const double f = eval(lobe, c);
  RC_ASSERT(f >= 0.0);
  RC_ASSERT(f <= 1.0);
  RC_ASSERT(eval(lobe, -c) == (c == 0 ? eval(lobe, 0.0) : 0.0));
  RC_ASSERT(eval(lobe, 0.0) == 0.0);
}

RC_GTEST_PROP(LobeProperties, MonotoneInC, ()) {
  const Lobe lobe = *any_lobe();
  const double a = *unit_interval(), b = *unit_interval();
  const double lo = std::min(a, b), hi = std::max(a, b);
  RC_ASSERT(eval(lobe, lo) <= eval(lobe, hi));
}

// ---- the enums of the vocabulary: Form, simd::Tier, simd::Family ------------------------------

TEST(Form, EveryFormRoundTripsByName) {
  for (const Form form : enumerators<Form, kFormCount>()) {
    ASSERT_TRUE(form_named(to_string(form))) << to_string(form);
    EXPECT_EQ(*form_named(to_string(form)), form);
  }
  EXPECT_STREQ(to_string(Form::rv), "rv");
  EXPECT_STREQ(to_string(Form::nh), "nh");
  EXPECT_EQ(form_named("RV"), std::nullopt);
  EXPECT_EQ(form_named(""), std::nullopt);
  EXPECT_EQ((names_listed<Form, kFormCount>([](Form f) { return to_string(f); })), "rv or nh");
}

TEST(Tier, EveryTierHasItsName) {
  std::set<std::string> names;
  for (const simd::Tier tier : enumerators<simd::Tier, simd::kTierCount>()) names.insert(simd::to_string(tier));
  EXPECT_EQ(names, (std::set<std::string>{"exact", "fast"}));
}

// simd::Family names Lobe's alternatives one for one (also a static_assert in lobes.h).
TEST(Family, OneEnumeratorPerLobeAlternative) { EXPECT_EQ(std::variant_size_v<Lobe>, simd::kFamilyCount); }

// The negative controls of names_complete (exceptions.h), at compile time: what a switch of names
// that is wrong for its count looks like, and that the check refuses it.
enum class Three { a, b, c };
constexpr const char* three_name(Three t) {
  switch (t) {
    case Three::a: return "a";
    case Three::b: return "b";
    case Three::c: return "c";
  }
  return "";
}
constexpr const char* three_missing(Three t) { return t == Three::b ? "" : three_name(t); }
constexpr const char* three_repeated(Three t) { return t == Three::c ? "a" : three_name(t); }
static_assert(names_complete<Three, 3>(three_name));
static_assert(!names_complete<Three, 2>(three_name), "c added after the count's last enumerator");
static_assert(!names_complete<Three, 4>(three_name), "a count past the enum");
static_assert(!names_complete<Three, 3>(three_missing), "an enumerator without a name");
static_assert(!names_complete<Three, 3>(three_repeated), "two enumerators with one name");
static_assert(enum_named<Three, 3>("c", three_name) == Three::c);
static_assert(!enum_named<Three, 3>("d", three_name));

TEST(EnumNames, ListsAndEnumerators) {
  EXPECT_EQ((names_listed<Three, 3>(three_name)), "a, b or c");
  EXPECT_EQ((names_listed<Three, 3>(three_name, " | ", " | ")), "a | b | c");
  EXPECT_EQ((names_listed<Three, 1>(three_name)), "a");
  EXPECT_EQ((enumerators<Three, 3>()), (std::array{Three::a, Three::b, Three::c}));
}

}  // namespace
}  // namespace specula::lobes
