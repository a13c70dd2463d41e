// src/fit/simplified.h: a fitted formula is replaced by its simplified form only where that
// computes the same on the training rows, is no larger, and uses what the search allows.
#include "fit/simplified.h"

#include "fit/constants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "specula/expr/expr.h"

namespace specula::fit {
namespace {

struct Case {
  std::vector<double> x;
  Rows rows;
  std::vector<double> predicted;

  Case(std::vector<double> xs, const Genome& g) : x(std::move(xs)) {
    rows.columns = {x};
    predicted.resize(x.size());
    expr::evaluate_batch(expr::Expression(g, {"v0"}), rows.columns, predicted);
  }
};

Genome genome(const char* text) {
  const expr::Expression e = expr::parse(text, {"v0"});
  return {e.nodes().begin(), e.nodes().end()};
}

std::string text(const Genome& g) { return expr::to_infix(expr::Expression(g, {"v0"})); }

/// g simplified, or g where simplified() keeps it.
Genome simplified_or_same(const Genome& g, std::span<const double> predicted, const Rows& rows, const SimplifyRules& rules) {
  const auto simple = simplified(g, predicted, rows, rules);
  return simple ? *simple : g;
}

SimplifyRules all_operators() {
  return {{expr::Op::add, expr::Op::sub, expr::Op::mul, expr::Op::div, expr::Op::pow, expr::Op::sqrt}, Constants::fitted, {}, {}};
}

TEST(Simplified, ReplacesAFormulaThatComputesTheSame) {
  const Genome g = genome("v0 * 2 + v0 * 3");
  const Case c({0.5, 1, 2, 3}, g);
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, all_operators())), "5 * v0");
}

// Without ^ among the operators, the powers the simplifier makes (v0·v0 → v0²) go back to
// products, and the rest of its work stays: here the double negation a − (−b − c)/d.
TEST(Simplified, WritesPowersAsProductsWhenTheOperatorsHaveNoPower) {
  const Genome g = genome("v0 - (-2 * v0 - 3) / (v0 * v0 + 1)");
  const Case c({0.5, 1, 2, 3}, g);
  const SimplifyRules no_power{{expr::Op::add, expr::Op::sub, expr::Op::mul, expr::Op::div}, Constants::fitted, {}, {}};
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, no_power)), "v0 + (2 * v0 + 3) / (v0 * v0 + 1)");
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, all_operators())), "v0 + (2 * v0 + 3) / (v0 ^ 2 + 1)");
  const Genome reciprocal = genome("v0 / (v0 * v0 * v0)");  // v0^-2: 1 / (v0 · v0)
  const Case r({0.5, 1, 2, 3}, reciprocal);
  EXPECT_EQ(text(simplified_or_same(reciprocal, r.predicted, r.rows, no_power)), "1 / (v0 * v0)");
  const SimplifyRules no_division{{expr::Op::add, expr::Op::mul}, Constants::fitted, {}, {}};  // the control
  EXPECT_EQ(text(simplified_or_same(reciprocal, r.predicted, r.rows, no_division)), "v0 / (v0 * v0 * v0)");
}

TEST(Simplified, KeepsAFormulaWhoseRewriteChangesItsValuesOnTheData) {
  // √x·√x is x only where x ≥ 0: with a negative row the data refuses the rewrite.
  const Genome g = genome("sqrt(v0) * sqrt(v0)");
  const Case negative({-1, 1, 2}, g);
  EXPECT_EQ(text(simplified_or_same(g, negative.predicted, negative.rows, all_operators())), "sqrt(v0) * sqrt(v0)");
  const Case positive({0.5, 1, 2}, g);
  EXPECT_EQ(text(simplified_or_same(g, positive.predicted, positive.rows, all_operators())), "v0");
}

// v0·v0 becomes v0^2 with an exact exponent: the next fit of a formula holding it moves only the
// free constants. Were the 2 free, its derivative (v0^2·ln v0) is undefined at v0 < 0, and the
// fit of the other constant fails with it.
TEST(Simplified, APowerItMakesLeavesTheOtherConstantsFittable) {
  const Genome g = genome("v0 * v0 * exp(1 * v0)");
  std::vector<double> x, y;
  for (int i = 0; i <= 20; ++i) {
    x.push_back(-1 + i / 10.0);
    y.push_back(x.back() * x.back() * std::exp(0.7 * x.back()));
  }
  Case c(x, g);
  c.rows.target = y;
  SimplifyRules rules = all_operators();
  rules.operators.push_back(expr::Op::exp);
  Genome simple = simplified_or_same(g, c.predicted, c.rows, rules);
  ASSERT_EQ(text(simple), "v0 ^ 2 * exp(v0)");
  simple.insert(simple.begin() + 3, expr::Node{expr::Op::constant, 0, 1.0});  // exp(c·v0) again
  simple.insert(simple.begin() + 5, expr::Node{expr::Op::mul, 0, 0});
  ASSERT_EQ(text(simple), "v0 ^ 2 * exp(1 * v0)");
  fit_constants(simple, c.rows, Constants::fitted);
  EXPECT_EQ(simple[1].value, 2);
  EXPECT_NEAR(simple[3].value, 0.7, 1e-12) << text(simple);
}

TEST(ReliesOnCancellation, FlagsSumsThatLoseDigitsOnEveryRow) {
  std::vector<double> x;
  for (int i = 1; i <= 20; ++i) x.push_back(i / 20.0);
  Rows rows;
  rows.columns = {x};
  rows.target = x;
  const auto cancels = [&](const char* text) { return relies_on_cancellation(genome(text), rows); };
  EXPECT_TRUE(cancels("1573607.28 - 0.99999936 ^ v0 * 1573606.29"));
  EXPECT_TRUE(cancels("1105270 - 0.197243 * (5603590 - v0)"));
  EXPECT_TRUE(cancels("1e7 * v0 - 1e7 * (v0 - 5e-8)"));
  // Negative controls: cancellation near one end only, none at all, or no constant to fit.
  EXPECT_FALSE(cancels("sin(v0) - v0 * 1"));
  EXPECT_FALSE(cancels("1000 + v0"));
  EXPECT_FALSE(cancels("1 - v0"));
  EXPECT_FALSE(cancels("v0 - v0"));
}

TEST(Simplified, UsesOnlyTheOperatorsTheSearchAllows) {
  const Genome g = genome("v0 * v0");
  const Case c({0.5, 1, 2}, g);
  SimplifyRules no_pow = all_operators();
  no_pow.operators = {expr::Op::add, expr::Op::mul};
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, no_pow)), "v0 * v0");
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, all_operators())), "v0 ^ 2");
}

TEST(Simplified, KeepsIntegerConstantsInIntegerMode) {
  const Genome g = genome("v0 ^ 2 * v0 ^ -0.5");
  const Case c({0.5, 1, 2}, g);
  SimplifyRules integer = all_operators();
  integer.constants = Constants::integer;
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, integer)), text(g));
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, all_operators())), "v0 ^ 1.5");
}

TEST(Simplified, NeverGrowsAFormula) {
  const Genome g = genome("v0 ^ -2");  // written back it would be 1 / v0 ^ 2, two nodes more
  const Case c({0.5, 1, 2}, g);
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, all_operators())), "v0 ^ -2");
}

// A variable positive on every row is positive: the sign rules apply (√(v0²)·log(v0³) is 3·v0·log v0
// there), and a column with a row ≤ 0 gives no such fact (the control keeps the formula).
TEST(Simplified, UsesTheSignsTheDataShow) {
  const Genome g = genome("sqrt(v0 ^ 2) * log(v0 ^ 3)");
  const Case c({0.5, 1.5, 2, 3}, g);
  SimplifyRules rules = all_operators();
  rules.operators.push_back(expr::Op::log);
  rules.positive = positive_columns(c.rows.columns);
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, rules)), "3 * v0 * log(v0)");
  const Case signed_rows({-0.5, 1.5, 2, 3}, g);
  rules.positive = positive_columns(signed_rows.rows.columns);
  EXPECT_EQ(rules.positive, std::vector<bool>{false});
  EXPECT_EQ(text(simplified_or_same(g, signed_rows.predicted, signed_rows.rows, rules)), text(g));
}

}  // namespace
}  // namespace specula::fit
