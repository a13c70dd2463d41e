// specula::io value lists and ranges (include/specula/io/values.h): every form, exact expected
// vectors, every malformed kind, and round-trip / range properties.
#include "specula/io/values.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "specula/exceptions.h"

namespace specula::io {
namespace {

using ::testing::ElementsAre;
using ::testing::ElementsAreArray;
using ::testing::HasSubstr;

// The message of the InvalidArgument that parse_values(spec) throws ("" if it throws none).
std::string error_of(const std::string& spec) {
  try {
    (void)parse_values(spec);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

// ---- lists ----------------------------------------------------------------------------------

TEST(ParseValues, SingleNumber) {
  EXPECT_THAT(parse_values("5"), ElementsAre(5.0));
  EXPECT_THAT(parse_values("-2.5"), ElementsAre(-2.5));
  EXPECT_THAT(parse_values("+3"), ElementsAre(3.0));
  EXPECT_THAT(parse_values("1e3"), ElementsAre(1000.0));
  EXPECT_THAT(parse_values("0.1"), ElementsAre(0.1));
}

TEST(ParseValues, CommaList) {
  EXPECT_THAT(parse_values("1,2,5"), ElementsAre(1.0, 2.0, 5.0));
  EXPECT_THAT(parse_values("0.5,-1,1e-3"), ElementsAre(0.5, -1.0, 1e-3));
  // Order and duplicates are kept as given.
  EXPECT_THAT(parse_values("3,1,3"), ElementsAre(3.0, 1.0, 3.0));
}

// ---- a:b ------------------------------------------------------------------------------------

TEST(ParseValues, IntegerRange) {
  EXPECT_THAT(parse_values("1:7"), ElementsAre(1, 2, 3, 4, 5, 6, 7));
  EXPECT_THAT(parse_values("-2:1"), ElementsAre(-2, -1, 0, 1));
  EXPECT_THAT(parse_values("4:4"), ElementsAre(4.0));
  EXPECT_THAT(parse_values("1.0:3.0"), ElementsAre(1, 2, 3));  // integral values written as decimals
}

// ---- a:b:step -------------------------------------------------------------------------------

TEST(ParseValues, SteppedRange) {
  EXPECT_THAT(parse_values("0:10:5"), ElementsAre(0, 5, 10));
  EXPECT_THAT(parse_values("0:90:30"), ElementsAre(0, 30, 60, 90));
  EXPECT_THAT(parse_values("1:2:0.5"), ElementsAre(1.0, 1.5, 2.0));
  // The end need not be on the grid: a, a+step, … ≤ b.
  EXPECT_THAT(parse_values("0:10:3"), ElementsAre(0, 3, 6, 9));
  EXPECT_THAT(parse_values("0:1:2"), ElementsAre(0.0));
}

TEST(ParseValues, SteppedRangeEndsExactlyOnBDespiteRoundOff) {
  // (1 - 0)/0.1 = 9.999999999999998 in doubles: still 11 values, the last exactly 1.
  const auto v = parse_values("0:1:0.1");
  ASSERT_EQ(v.size(), 11u);
  EXPECT_EQ(v.front(), 0.0);
  EXPECT_EQ(v.back(), 1.0);
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR(v[i], 0.1 * static_cast<double>(i), 1e-15);

  // Ranges whose naive last value a + step·i lands an ulp off b.
  struct Case {
    const char* spec;
    std::size_t size;
    double last;
  };
  for (const auto& c : {Case{"0:0.3:0.1", 4, 0.3}, Case{"0:0.7:0.1", 8, 0.7},
                        Case{"0:0.9:0.3", 4, 0.9}, Case{"0.1:0.7:0.2", 4, 0.7},
                        Case{"0:1:0.01", 101, 1.0}, Case{"-1:1:0.1", 21, 1.0}}) {
    SCOPED_TRACE(c.spec);
    const auto w = parse_values(c.spec);
    ASSERT_EQ(w.size(), c.size);
    EXPECT_EQ(w.back(), c.last);
    for (const double x : w) EXPECT_LE(x, c.last);  // "a, a+step, … ≤ b"
    for (std::size_t i = 1; i < w.size(); ++i) EXPECT_LT(w[i - 1], w[i]);
  }
}

// ---- a:b@count ------------------------------------------------------------------------------

TEST(ParseValues, CountedLinearRange) {
  EXPECT_THAT(parse_values("0:1@5"), ElementsAre(0.0, 0.25, 0.5, 0.75, 1.0));
  EXPECT_THAT(parse_values("0.9:1@3"), ElementsAre(0.9, 0.95, 1.0));
  EXPECT_THAT(parse_values("-1:1@3"), ElementsAre(-1.0, 0.0, 1.0));
  EXPECT_THAT(parse_values("2:4@2"), ElementsAre(2.0, 4.0));
}

TEST(ParseValues, CountedRangeEndsExactlyOnB) {
  for (const char* spec : {"0:1@11", "0:0.3@7", "0.1:0.7@13", "1:1000@50", "0:1@1000", "-5.5:3.3@9"}) {
    SCOPED_TRACE(spec);
    const auto v = parse_values(spec);
    const std::string s = spec;
    const double b = std::stod(s.substr(s.find(':') + 1));
    EXPECT_EQ(v.back(), b);
  }
}

TEST(ParseValues, CountedLogRange) {
  const auto v = parse_values("1:1000@4:log");
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v.front(), 1.0);
  EXPECT_NEAR(v[1], 10.0, 1e-13);
  EXPECT_NEAR(v[2], 100.0, 1e-12);
  EXPECT_EQ(v.back(), 1000.0);

  const auto w = parse_values("0.001:1e6@50:log");
  ASSERT_EQ(w.size(), 50u);
  EXPECT_EQ(w.front(), 0.001);
  EXPECT_EQ(w.back(), 1e6);
  const double ratio = std::pow(1e9, 1.0 / 49.0);
  for (std::size_t i = 1; i < w.size(); ++i) EXPECT_NEAR(w[i] / w[i - 1], ratio, 1e-12 * ratio) << i;
}

// a:b@count:powK: evenly spaced in x^(1/K), the ends exact; √ spacing at K = 2, the K of one
// range only (a list or a linear range has 1).
TEST(ParseValues, CountedPowerRange) {
  const auto v = parse_values("0:1@3:pow2");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v.front(), 0.0);
  EXPECT_NEAR(v[1], 0.25, 1e-15);
  EXPECT_EQ(v.back(), 1.0);
  const auto w = parse_values("0.001:1@9:pow3");
  for (std::size_t i = 2; i < w.size(); ++i)
    EXPECT_NEAR(std::cbrt(w[i]) - std::cbrt(w[i - 1]), std::cbrt(w[1]) - std::cbrt(w[0]), 1e-14) << i;
  EXPECT_LT(w[1] - w[0], w[8] - w[7]);  // crowded toward the start
  EXPECT_EQ(parse_values("0.05:1@4:pow1"), parse_values("0.05:1@4"));
  EXPECT_EQ(spacing_power("0:1@32:pow4"), 4.0);
  EXPECT_EQ(spacing_power("0.5:1@3:pow2.5"), 2.5);
  for (const char* spec : {"0:1@32", "1:100@3:log", "0:1@3:pow2,2", "0.1,0.2", "paper50"}) EXPECT_EQ(spacing_power(spec), 1.0) << spec;
}

// ---- paper50 --------------------------------------------------------------------------------

TEST(ParseValues, Paper50) {
  const std::vector<double> expected{1,   2,   3,   4,   5,   6,   7,   8,   9,   10,  11,  12,  13,
                                     14,  15,  16,  17,  18,  19,  20,  21,  22,  23,  26,  29,  34,
                                     39,  45,  52,  60,  69,  79,  91,  105, 121, 139, 160, 184, 212,
                                     244, 281, 324, 373, 429, 494, 569, 655, 754, 869, 1000};
  EXPECT_THAT(paper50(), ElementsAreArray(expected));
  EXPECT_THAT(parse_values("paper50"), ElementsAreArray(expected));

  const auto p = paper50();
  ASSERT_EQ(p.size(), 50u);
  for (int i = 0; i < 7; ++i) EXPECT_EQ(p[i], i + 1);  // 1…7 like the paper's Fig. 5
  EXPECT_EQ(p.back(), 1000.0);
  for (std::size_t i = 1; i < p.size(); ++i) {
    EXPECT_LT(p[i - 1], p[i]);
    EXPECT_EQ(p[i], std::floor(p[i]));
  }
}

// ---- combined -------------------------------------------------------------------------------

TEST(ParseValues, ItemsCombineWithCommas) {
  EXPECT_THAT(parse_values("0.5,1:4,100"), ElementsAre(0.5, 1, 2, 3, 4, 100));
  EXPECT_THAT(parse_values("0:1@3,5:9:2,-1"), ElementsAre(0.0, 0.5, 1.0, 5, 7, 9, -1));
  EXPECT_THAT(parse_values("1:100@3:log,7"), ElementsAre(1.0, ::testing::DoubleNear(10, 1e-13), 100.0, 7));
  const auto v = parse_values("0,paper50,2000");
  ASSERT_EQ(v.size(), 52u);
  EXPECT_EQ(v.front(), 0.0);
  EXPECT_EQ(v[1], 1.0);
  EXPECT_EQ(v[50], 1000.0);
  EXPECT_EQ(v.back(), 2000.0);
}

// ---- malformed ------------------------------------------------------------------------------

TEST(ParseValues, EmptyThrows) {
  const std::string message = error_of("");
  EXPECT_THAT(message, HasSubstr("empty"));
}

TEST(ParseValues, EveryMalformedKindThrowsNamingTheItem) {
  // {spec, the item the message must name}
  const std::vector<std::pair<std::string, std::string>> cases{
      {"1:", "1:"},
      {":5", ":5"},
      {"a:b", "a:b"},
      {"1:2:0", "1:2:0"},
      {"1:2:-1", "1:2:-1"},
      {"5:1", "5:1"},
      {"5:1:0.5", "5:1:0.5"},
      {"1:2@0", "1:2@0"},
      {"1:2@-3", "1:2@-3"},
      {"1:2@2.5", "1:2@2.5"},
      {"1:2@abc", "1:2@abc"},
      {"1:2@", "1:2@"},
      {"0:1@5:log", "0:1@5:log"},
      {"-1:10@5:log", "-1:10@5:log"},
      {"1:2@5:lin", "1:2@5:lin"},
      {"1:2@5:log:log", "1:2@5:log:log"},
      {"1:2@5:pow", "1:2@5:pow"},
      {"1:2@5:pow0", "1:2@5:pow0"},
      {"1:2@5:pow-2", "1:2@5:pow-2"},
      {"1:2@5:pownan", "1:2@5:pownan"},
      {"-1:2@5:pow2", "-1:2@5:pow2"},
      {"1:2:0.5@3", "1:2:0.5@3"},
      {"1:2:3:4", "1:2:3:4"},
      {"1@3", "1@3"},
      {"nan", "nan"},
      {"-nan", "-nan"},
      {"inf", "inf"},
      {"-inf", "-inf"},
      {"1e999", "1e999"},
      {"1:1e999", "1:1e999"},
      {"1,,2", "1,,2"},
      {"1,", "1,"},
      {",1", ",1"},
      {"1.5:3", "1.5:3"},
      {"1:3.5", "1:3.5"},
      {"x", "x"},
      {"1x", "1x"},
      {" 1", " 1"},
      {"1 ", "1 "},
      {"0x10", "0x10"},
      {"++1", "++1"},
      {"Paper50", "Paper50"},
      {"1,2,oops", "oops"},
  };
  for (const auto& [spec, item] : cases) {
    SCOPED_TRACE("spec '" + spec + "'");
    const std::string message = error_of(spec);
    ASSERT_FALSE(message.empty()) << "no InvalidArgument; parse_values returned";
    EXPECT_THAT(message, HasSubstr("'" + item + "'"));
  }
}

TEST(ParseValues, AGivenCapIsCheckedBeforeARangeExpands) {
  EXPECT_THAT(parse_values("1:5", 5), ElementsAre(1, 2, 3, 4, 5));
  EXPECT_THAT(parse_values("1,2:3,paper50", 53), ::testing::SizeIs(53));
  for (const std::string spec : {"1:6", "0:1@6", "1,2,3,4,5,6", "1:3,4:6", "1:1000000000", "paper50"}) {
    SCOPED_TRACE(spec);
    try {
      (void)parse_values(spec, 5);
      ADD_FAILURE() << "no InvalidArgument";
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr("more than 5 values"));
    }
  }
}

TEST(ParseValues, MoreThanMaxValuesThrows) {
  const auto max = kMaxValues;
  for (const std::string& spec : {fmt::format("1:{}", max + 1), fmt::format("0:1@{}", max + 1),
                                 fmt::format("0:1@{}:log", max + 1), std::string("0:1:1e-8"),
                                 std::string("0:1e308:1e-308"), std::string("-1e308:1e308:1"),
                                 std::string("0:1:5e-324")}) {
    SCOPED_TRACE(spec);
    const std::string message = error_of(spec);
    ASSERT_FALSE(message.empty());
    EXPECT_THAT(message, HasSubstr(fmt::format("{}", max)));
    EXPECT_THAT(message, HasSubstr("'" + spec + "'"));
  }
  // Items each within the limit, together over it.
  const std::string spec = fmt::format("1:{},1:{}", max / 2, max / 2 + 1);
  const std::string message = error_of(spec);
  ASSERT_FALSE(message.empty());
  EXPECT_THAT(message, HasSubstr(fmt::format("{}", max)));
}

// Found by fuzz/values_fuzz.cpp (fuzz/corpus/values/wide_count, wide_count_log): where b − a or
// b / a overflows, the ends of the range of a double still give finite values, and a step range
// across it is counted, not refused as too many.
TEST(ParseValues, RangesAcrossTheWholeRangeOfADoubleStayFinite) {
  EXPECT_EQ(parse_values("-1e308:1e308@3"), (std::vector<double>{-1e308, 0, 1e308}));
  EXPECT_EQ(parse_values("-1e308:1e308:1e308"), (std::vector<double>{-1e308, 0, 1e308}));
  const auto log = parse_values("1e-300:1e300@3:log");
  ASSERT_EQ(log.size(), 3u);
  EXPECT_EQ(log[0], 1e-300);
  EXPECT_NEAR(log[1], 1, 1e-12);
  EXPECT_EQ(log[2], 1e300);
  const auto down = parse_values("1e300:1e-300@5:log");
  for (const double v : down) EXPECT_TRUE(std::isfinite(v) && v >= 1e-300 && v <= 1e300) << v;
}

TEST(ParseValues, ThrowsTheLibrarysOwnException) {
  EXPECT_THROW((void)parse_values("1:"), InvalidArgument);
  EXPECT_THROW((void)parse_values("nan"), InvalidArgument);
  EXPECT_THROW((void)parse_values(""), InvalidArgument);
}

// ---- parse_number ---------------------------------------------------------------------------

TEST(ParseNumber, AcceptsWholeFiniteNumbers) {
  EXPECT_EQ(parse_number("1", "x"), 1.0);
  EXPECT_EQ(parse_number("-0.25", "x"), -0.25);
  EXPECT_EQ(parse_number("+2", "x"), 2.0);
  EXPECT_EQ(parse_number("1e-300", "x"), 1e-300);
  EXPECT_EQ(parse_number("1.7976931348623157e308", "x"), 1.7976931348623157e308);
}

TEST(ParseNumber, RejectsTrailingGarbageAndNonFinite) {
  for (const char* text : {"1x", "1 ", " 1", "", "+", "-", "1,2", "1:2", "e5", "nan", "inf", "1e999",
                           "--1", "+-1", "1e", "0x1p3"}) {
    SCOPED_TRACE(fmt::format("'{}'", text));
    try {
      (void)parse_number(text, "--thing");
      ADD_FAILURE() << "accepted";
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr("--thing"));
      EXPECT_THAT(e.what(), HasSubstr(fmt::format("'{}'", text)));
    }
  }
}

// ---- properties -----------------------------------------------------------------------------

// Any finite double, from its bits: covers subnormals, huge and tiny exponents, -0.
rc::Gen<double> finite_double() {
  return rc::gen::suchThat(
      rc::gen::map(rc::gen::arbitrary<std::uint64_t>(), [](std::uint64_t b) { return std::bit_cast<double>(b); }),
      [](double x) { return std::isfinite(x); });
}

RC_GTEST_PROP(ParseValuesProperty, ShortestTextRoundTrips, ()) {
  const double x = *finite_double();
  const std::string text = fmt::format("{}", x);
  const auto v = parse_values(text);
  RC_ASSERT(v.size() == 1u);
  RC_ASSERT(std::bit_cast<std::uint64_t>(v[0]) == std::bit_cast<std::uint64_t>(x));
}

RC_GTEST_PROP(ParseValuesProperty, SmallAndNamedDoublesRoundTrip, ()) {
  const double x = *rc::gen::arbitrary<double>();
  RC_PRE(std::isfinite(x));
  const auto v = parse_values(fmt::format("{}", x));
  RC_ASSERT(v.size() == 1u);
  RC_ASSERT(v[0] == x);
}

RC_GTEST_PROP(ParseValuesProperty, CountedRangeHasCountValuesFromAToB, ()) {
  const auto magnitude = *rc::gen::element(1e-6, 1.0, 1e3, 1e9);
  const double x = *rc::gen::map(rc::gen::inRange(-1'000'000'000, 1'000'000'001),
                                 [&](int i) { return i * magnitude / 1e9; });
  const double y = *rc::gen::map(rc::gen::inRange(-1'000'000'000, 1'000'000'001),
                                 [&](int i) { return i * magnitude / 1e9; });
  RC_PRE(x != y);
  const double a = std::min(x, y), b = std::max(x, y);
  const int count = *rc::gen::inRange(2, 1001);
  const auto v = parse_values(fmt::format("{}:{}@{}", a, b, count));
  RC_ASSERT(v.size() == static_cast<std::size_t>(count));
  RC_ASSERT(v.front() == a);
  RC_ASSERT(v.back() == b);
  for (std::size_t i = 1; i < v.size(); ++i) RC_ASSERT(v[i - 1] <= v[i]);
}

RC_GTEST_PROP(ParseValuesProperty, CountedLogRangeHasConstantRatio, ()) {
  const double a = std::ldexp(1.0, *rc::gen::inRange(-30, 30)) * *rc::gen::inRange(1, 1000);
  const double b = a * *rc::gen::inRange(2, 100000);
  const int count = *rc::gen::inRange(2, 200);
  const auto v = parse_values(fmt::format("{}:{}@{}:log", a, b, count));
  RC_ASSERT(v.size() == static_cast<std::size_t>(count));
  RC_ASSERT(v.front() == a);
  RC_ASSERT(v.back() == b);
  const double ratio = std::pow(b / a, 1.0 / (count - 1));
  for (std::size_t i = 1; i < v.size(); ++i) RC_ASSERT(std::abs(v[i] / v[i - 1] / ratio - 1) < 1e-12);
}

RC_GTEST_PROP(ParseValuesProperty, SteppedRangeStaysWithinAToB, ()) {
  const int a = *rc::gen::inRange(-1000, 1000);
  const int span = *rc::gen::inRange(0, 1000);
  const int tenths = *rc::gen::inRange(1, 50);
  const double step = tenths / 10.0;  // 0.1, 0.2, …: not exact in binary
  const double b = a + span / 10.0;
  const auto v = parse_values(fmt::format("{}:{}:{}", a, b, step));
  const auto expected = static_cast<std::size_t>(span / tenths) + 1;  // exact in integers
  RC_ASSERT(v.size() == expected);
  RC_ASSERT(v.front() == static_cast<double>(a));
  for (const double x : v) RC_ASSERT(x <= b);
  if (span % tenths == 0) RC_ASSERT(v.back() == b);
}

}  // namespace
}  // namespace specula::io
