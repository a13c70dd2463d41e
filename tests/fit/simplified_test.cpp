// src/fit/simplified.h: a fitted formula is replaced by its simplified form only where that
// computes the same on the training rows, is no larger, and uses what the search allows.
#include "fit/simplified.h"

#include <gtest/gtest.h>

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
  return {{expr::Op::add, expr::Op::sub, expr::Op::mul, expr::Op::div, expr::Op::pow, expr::Op::sqrt}, Constants::fitted, {}};
}

TEST(Simplified, ReplacesAFormulaThatComputesTheSame) {
  const Genome g = genome("v0 * 2 + v0 * 3");
  const Case c({0.5, 1, 2, 3}, g);
  EXPECT_EQ(text(simplified_or_same(g, c.predicted, c.rows, all_operators())), "5 * v0");
}

TEST(Simplified, KeepsAFormulaWhoseRewriteChangesItsValuesOnTheData) {
  // √x·√x is x only where x ≥ 0: with a negative row the data refuses the rewrite.
  const Genome g = genome("sqrt(v0) * sqrt(v0)");
  const Case negative({-1, 1, 2}, g);
  EXPECT_EQ(text(simplified_or_same(g, negative.predicted, negative.rows, all_operators())), "sqrt(v0) * sqrt(v0)");
  const Case positive({0.5, 1, 2}, g);
  EXPECT_EQ(text(simplified_or_same(g, positive.predicted, positive.rows, all_operators())), "v0");
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

}  // namespace
}  // namespace specula::fit
