// Options of the search: metrics, operator lists, size weights, and the choice of a formula.
#include <gtest/gtest.h>

#include <numbers>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "specula/exceptions.h"
#include "specula/fit/fit.h"

namespace specula::fit {
namespace {

using expr::Op;

// As a float shader has them: 0.1 rounded to float, 1/3 as float(1)/float(3), π/4 in float.
TEST(FloatConstants, RoundAsAShaderDoes) {
  const expr::Expression third(std::vector<expr::Node>{expr::exact_constant(1, 3, expr::Symbol::one)}, {});
  EXPECT_EQ(expr::evaluate(float_constants(third), {}), static_cast<double>(1.0f / 3.0f));
  const expr::Expression quarter_pi(std::vector<expr::Node>{expr::exact_constant(1, 4, expr::Symbol::pi)}, {});
  EXPECT_EQ(expr::evaluate(float_constants(quarter_pi), {}), static_cast<double>(static_cast<float>(std::numbers::pi) / 4.0f));
  const expr::Expression tenth = expr::parse("0.1 * x", {"x"});
  const double x = 1;
  EXPECT_EQ(expr::evaluate(float_constants(tenth), std::span<const double>(&x, 1)), static_cast<double>(0.1f));
  EXPECT_NE(expr::evaluate(tenth, std::span<const double>(&x, 1)), static_cast<double>(0.1f));  // negative control
}

TEST(Measure, ComputesEachMetricByHand) {
  const std::vector<double> y{1, 2, 4}, f{1.5, 2, 3};  // errors 0.5, 0, -1
  EXPECT_DOUBLE_EQ(measure(Metric::rms, f, y), std::sqrt(1.25 / 3));
  EXPECT_DOUBLE_EQ(measure(Metric::mae, f, y), 0.5);
  EXPECT_DOUBLE_EQ(measure(Metric::max_abs, f, y), 1);
  EXPECT_DOUBLE_EQ(measure(Metric::mean_relative, f, y), (0.5 + 0.25) / 3);
  // SST = (1-7/3)² + (2-7/3)² + (4-7/3)² = 14/3, SSE = 1.25
  EXPECT_DOUBLE_EQ(measure(Metric::r2, f, y), 1 - 1.25 / (14.0 / 3));
  EXPECT_EQ(measure(Metric::rms, std::vector<double>{NAN, 2, 4}, y), INFINITY);
}

TEST(Metric, NamesRoundTrip) {
  for (Metric m : {Metric::rms, Metric::mae, Metric::max_abs, Metric::max_rel, Metric::mean_relative, Metric::r2})
    EXPECT_EQ(parse_metric(metric_name(m)), m);
  EXPECT_THROW(parse_metric("mse"), InvalidArgument);
  EXPECT_EQ(to_loss(Metric::r2, 0.75), 0.25);
}

// The option values' names, each from one switch in src/fit/options.cpp: every enumerator up to the
// count round-trips name → value → name, and the messages list exactly those names. (Their
// compile-time control is the static_assert(names_complete…) beside each switch: an enumerator
// added after the last one fails the build there until the count moves.)
TEST(OptionNames, EveryEnumeratorRoundTrips) {
  for (const Metric m : enumerators<Metric, kMetricCount>()) EXPECT_EQ(metric_name(parse_metric(metric_name(m))), metric_name(m));
  for (const Constants c : enumerators<Constants, kConstantsCount>()) {
    EXPECT_EQ(parse_constants(constants_name(c)), c);
    EXPECT_EQ(constants_name(parse_constants(constants_name(c))), constants_name(c));
  }
  for (const Split s : enumerators<Split, kSplitCount>()) {
    ASSERT_TRUE(split_named(split_name(s))) << split_name(s);
    EXPECT_EQ(*split_named(split_name(s)), s);
  }
  for (const Choice c : enumerators<Choice, kChoiceCount>()) {
    EXPECT_EQ(parse_choice(choice_name(c)), c);
    EXPECT_EQ(choice_name(parse_choice(choice_name(c))), choice_name(c));
  }
  EXPECT_EQ(split_named("first"), std::nullopt);
}

// Why a search stopped is an enum; its names are what `fit --format json` and the server's fit
// status print in stopped_by, as when they were strings.
TEST(OptionNames, StopReasonsKeepTheirNames) {
  std::vector<std::string_view> names;
  for (const StopReason r : enumerators<StopReason, kStopReasonCount>()) names.push_back(to_string(r));
  EXPECT_EQ(names, (std::vector<std::string_view>{"time", "generations", "evaluations", "target error", "cancelled"}));
}

// The messages as they were before the names came from one list, byte for byte.
TEST(OptionNames, MessagesListTheNames) {
  const auto message = [](auto parse, const char* text) {
    try {
      parse(text);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(parse_metric, "mse"), "unknown metric 'mse' (expected rms, mae, max-abs, max-rel, mean-relative or r2)");
  EXPECT_EQ(message(parse_constants, "all"), "unknown constants mode 'all' (expected fitted, integer or none)");
  EXPECT_EQ(message(parse_choice, "first"), "unknown choice 'first' (expected parsimonious, knee or best)");
  EXPECT_EQ((names_listed<Metric, kMetricCount>(metric_name, " | ", " | ")), "rms | mae | max-abs | max-rel | mean-relative | r2");
  EXPECT_EQ((names_listed<Split, kSplitCount>(split_name)), "random or last");
}

TEST(Operators, ParseSymbolsAndFunctionNames) {
  EXPECT_EQ(parse_operators("+,*,/"), (std::vector<Op>{Op::add, Op::mul, Op::div}));
  EXPECT_EQ(parse_operators("+, -, sin ,exp,+"), (std::vector<Op>{Op::add, Op::sub, Op::sin, Op::exp}));
  EXPECT_THROW(parse_operators("+,tan"), InvalidArgument);
  EXPECT_THROW(parse_operators(""), InvalidArgument);
}

// Every op expr knows, by every name --ops lists (operator_names() is what --help prints).
TEST(Operators, EveryOpParsesByTheNameTheHelpLists) {
  std::vector<Op> parsed;
  std::string name;
  for (std::istringstream names(operator_names()); names >> name;) {
    const auto ops = parse_operators(name);
    ASSERT_EQ(ops.size(), 1u) << name;
    parsed.push_back(ops.front());
  }
  for (std::size_t i = 0; i < expr::kOpCount; ++i) {
    const auto op = static_cast<Op>(i);
    const bool listed = std::find(parsed.begin(), parsed.end(), op) != parsed.end();
    EXPECT_EQ(listed, expr::arity(op) > 0) << "op " << i;
  }
}

// The weight table holds every op: setting one op's weight changes that op alone.
TEST(SizeWeights, EveryOperatorsWeightIsItsOwn) {
  std::string name;
  for (std::istringstream names(operator_names()); names >> name;) {
    const Op op = parse_operators(name).front();
    const auto w = SizeWeights::parse(name + "=7");
    for (std::size_t i = 0; i < expr::kOpCount; ++i) {
      const auto other = static_cast<Op>(i);
      EXPECT_EQ(w.of(other), other == op ? 7 : 1) << name << " changed op " << i;
    }
  }
  EXPECT_EQ(SizeWeights().of(Op::asin), 1);
  EXPECT_EQ(SizeWeights::parse("asin=100").of(Op::asin), 100);
  EXPECT_THROW(SizeWeights::parse("asin=101"), InvalidArgument);
}

TEST(SizeWeights, DefaultTuringbotAndOverrides) {
  const auto e = expr::parse("0.2*(n + 1.2) + 0.07/(0.6 + n)");
  EXPECT_EQ(SizeWeights().of(e.nodes()), 11);
  EXPECT_EQ(SizeWeights::parse("turingbot").of(e.nodes()), 12);  // the paper's size 12
  EXPECT_EQ(SizeWeights::parse("/=3, *=2").of(e.nodes()), 14);
  EXPECT_THROW(SizeWeights::parse("/=0"), InvalidArgument);
  EXPECT_THROW(SizeWeights::parse("/=1.5"), InvalidArgument);
  EXPECT_THROW(SizeWeights::parse("tan=2"), InvalidArgument);
}

Candidate candidate(int size, double train, std::optional<double> test = std::nullopt) {
  return {expr::parse("x"), size, train, test};
}

TEST(Choose, ParsimoniousKneeAndBest) {
  // The paper's front (Fig. 8, TuringBot's sizes and RMS).
  const std::vector<Candidate> front{candidate(1, 62.583411), candidate(3, 0.183519),
                                     candidate(5, 0.006839),  candidate(9, 0.006503),
                                     candidate(10, 0.001128), candidate(12, 0.000280),
                                     candidate(18, 0.000273)};
  EXPECT_EQ(choose(front, Metric::rms, Choice::parsimonious, 1.5, 1e-8), 5u);  // size 12
  EXPECT_EQ(choose(front, Metric::rms, Choice::best, 1.5, 1e-8), 6u);
  EXPECT_EQ(choose(front, Metric::rms, Choice::knee, 1.5, 1e-8), 2u);  // size 5
}

TEST(Choose, PrefersTestErrorAndTreatsR2AsHigherIsBetter) {
  const std::vector<Candidate> overfit{candidate(3, 0.1, 0.1), candidate(9, 0.01, 0.5)};
  EXPECT_EQ(choose(overfit, Metric::rms, Choice::best, 1.5, 1e-10), 0u);
  const std::vector<Candidate> r2{candidate(3, 0.9), candidate(7, 0.999)};
  EXPECT_EQ(choose(r2, Metric::r2, Choice::best, 1.5, 1e-10), 1u);
  EXPECT_THROW(choose({}, Metric::rms, Choice::best, 1.5, 1e-10), InvalidArgument);
}

// Issue 42's overfit: a size-23 formula whose large constants cancel fits the rows a little better
// than the size-15 truth, but printed with 6 digits its error is 1e-4: ranked by the printed
// error, the truth is chosen. The control: without the printed error the overfit wins.
TEST(Choose, RanksByThePrintedErrorSoCancellingConstantsCountAgainst) {
  Candidate truth = candidate(15, 1e-12), overfit = candidate(23, 1e-14);
  truth.printed_error = 1e-12;
  EXPECT_EQ(choose({truth, overfit}, Metric::rms, Choice::parsimonious, 1.5, 1e-16), 1u);
  overfit.printed_error = 1e-4;
  EXPECT_EQ(choose({truth, overfit}, Metric::rms, Choice::parsimonious, 1.5, 1e-16), 0u);
  EXPECT_EQ(choose({truth, overfit}, Metric::rms, Choice::best, 1.5, 1e-16), 0u);
}

// The noise floor: 1e-10 of the RMS for exact data, the rounding of the decimals (3 decimals:
// 0.001/√12 = 2.9e-4, times 1.25) where the best formula does not fit below it; integers that an
// exact formula fits to rounding (x(x + 1)/2) keep the 1e-10 floor.
TEST(NoiseFloor, IsTheDecimalsRoundingWhereTheBestFormulaStopsThere) {
  std::vector<double> three_decimals, integers;
  for (int i = 1; i <= 50; ++i) {
    three_decimals.push_back(std::round(1000 * (0.2 * i + 0.37 / i)) / 1000);
    integers.push_back(i * (i + 1) / 2.0);
  }
  const double rounding = 0.001 / std::sqrt(12.0);
  EXPECT_NEAR(noise_floor(three_decimals, Metric::rms, 2.8e-4), 1.25 * rounding, 0.05 * rounding);
  EXPECT_LT(noise_floor(three_decimals, Metric::rms, 1e-15), 1e-8);  // an exact fit: no rounding floor
  EXPECT_LT(noise_floor(integers, Metric::rms, 1e-15), 1e-7);
  EXPECT_LT(noise_floor(three_decimals, Metric::max_abs, 2.8e-4), 1e-8);  // RMS only
}

TEST(Rounded, KeepsSignificantDigits) {
  const auto e = rounded(expr::parse("0.19725431*n + 1.2389123e-5"), 3);
  EXPECT_EQ(expr::to_infix(e), "0.197 * n + 1.24e-05");
}

}  // namespace
}  // namespace specula::fit
