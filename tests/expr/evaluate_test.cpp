// specula::expr evaluation (include/specula/expr/expr.h): hand-computed values, IEEE special
// cases, and evaluate_batch agreeing bit for bit with evaluate on random expressions and data.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "expr/random_expression.h"
#include "specula/exceptions.h"
#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

double at(const std::string& text, double x, double y = 0) {
  return evaluate(parse(text, {"x", "y"}), std::vector{x, y});
}

TEST(Evaluate, HandComputedValues) {
  EXPECT_EQ(at("3 * x ^ 2 - 2 * x + 1", 2), 9.0);
  EXPECT_EQ(at("x / y + y / x", 1, 2), 2.5);
  EXPECT_DOUBLE_EQ(at("exp(log(x)) * sqrt(y)", 3, 4), 6.0);
  EXPECT_DOUBLE_EQ(at("sin(x) ^ 2 + cos(x) ^ 2", 0.7), 1.0);
  EXPECT_DOUBLE_EQ(at("acos(x)", 0.5), std::acos(0.5));
  EXPECT_EQ(at("log2(x) + abs(y)", 1024, -3), 13.0);
  EXPECT_EQ(at("min(x, y) * max(x, y)", 4, -2), -8.0);
  EXPECT_EQ(at("-x ^ 2", 3), -9.0);
}

TEST(Evaluate, IeeeSpecialCases) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(at("1 / x", 0), inf);
  EXPECT_EQ(at("1 / x", -0.0), -inf);
  EXPECT_TRUE(std::isnan(at("x / x", 0)));
  EXPECT_TRUE(std::isnan(at("sqrt(x)", -1)));
  EXPECT_EQ(at("log(x)", 0), -inf);
  EXPECT_TRUE(std::isnan(at("acos(x)", 2)));
}

TEST(Evaluate, MinAndMaxAreStdMinAndMax) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(std::isnan(at("min(x, y)", nan, 1)));
  EXPECT_EQ(at("min(x, y)", 1, nan), 1.0);
  EXPECT_TRUE(std::isnan(at("max(x, y)", nan, 1)));
  EXPECT_EQ(at("max(x, y)", 1, nan), 1.0);
}

TEST(Evaluate, DeepStacks) {
  std::string text = "x";
  for (int i = 0; i < 40; ++i) text = "(1 + " + text + ")";  // right operands nest: depth 41
  std::string sum = "x";
  for (int i = 0; i < 40; ++i) sum = "x + (" + sum + ")";
  const Expression e = parse(sum, {"x"});
  EXPECT_EQ(e.stack_depth(), 41u);
  EXPECT_EQ(evaluate(e, std::vector{1.0}), 41.0);
  const std::vector<double> column(300, 2.0);
  const std::vector<std::span<const double>> columns{column};
  std::vector<double> out(300);
  evaluate_batch(e, columns, out);
  EXPECT_EQ(out.front(), 82.0);
  EXPECT_EQ(out.back(), 82.0);
  EXPECT_EQ(at(text, 1), 41.0);
}

TEST(Evaluate, RejectsMissingVariables) {
  const Expression e = parse("x + y");
  EXPECT_THROW((void)evaluate(e, std::vector{1.0}), InvalidArgument);
  const std::vector<double> x(3), y(2);
  std::vector<double> out(3);
  EXPECT_THROW(evaluate_batch(e, std::vector<std::span<const double>>{x}, out), InvalidArgument);
  EXPECT_THROW(evaluate_batch(e, std::vector<std::span<const double>>{x, y}, out), InvalidArgument);
}

TEST(EvaluateBatch, EmptyOutput) {
  std::vector<double> out;
  EXPECT_NO_THROW(evaluate_batch(parse("1 + 2"), {}, out));
}

bool same_bits_or_both_nan(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) ||
         std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

RC_GTEST_PROP(EvaluateBatch, EqualsScalarEvaluation, ()) {
  const Expression e = *testing::random_expression();
  const auto rows = *rc::gen::inRange<std::size_t>(0, 700);  // several chunks and a partial one
  std::mt19937_64 random(*rc::gen::arbitrary<std::uint64_t>());
  std::uniform_real_distribution<double> uniform(-4.0, 4.0);
  std::vector<double> x(rows), y(rows), out(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    x[r] = uniform(random);
    y[r] = uniform(random);
  }
  const std::vector<std::span<const double>> columns{x, y};
  evaluate_batch(e, columns, out);
  for (std::size_t r = 0; r < rows; ++r)
    RC_ASSERT(same_bits_or_both_nan(out[r], evaluate(e, std::vector{x[r], y[r]})));
}

}  // namespace
}  // namespace specula::expr
