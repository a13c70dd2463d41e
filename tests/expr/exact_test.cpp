// Exact constants (expr::exact_constant, Node::numerator/denominator/symbol): their values, how
// every printer writes them, that the infix text reads back to the same value, and that
// simplify() keeps them exact.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "specula/expr/expr.h"
#include "specula/expr/simplify.h"

namespace specula::expr {
namespace {

/// x · c.
Expression times_x(const Node& c) { return Expression({Node{Op::variable, 0, 0}, c, Node{Op::mul, 0, 0}}, {"x"}); }
Expression alone(const Node& c) { return Expression({c}, {}); }

TEST(Exact, ValuesAreWhatTheirTextComputes) {
  EXPECT_EQ(exact_constant(1, 3, Symbol::one).value, 1.0 / 3.0);
  EXPECT_EQ(exact_constant(3, 4, Symbol::pi).value, 3 * std::numbers::pi / 4);
  EXPECT_EQ(exact_constant(-1, 2, Symbol::sqrt2).value, -std::sqrt(2.0) / 2);
  EXPECT_EQ(exact_constant(2, 1, Symbol::ln2).value, 2 * std::log(2.0));
}

TEST(Exact, EveryPrinterWritesTheFraction) {
  const Expression third = alone(exact_constant(1, 3, Symbol::one));
  EXPECT_EQ(to_infix(third), "1 / 3");
  EXPECT_EQ(to_cpp(third), "1.0 / 3.0");
  EXPECT_EQ(to_glsl(third), "1.0 / 3.0");
  EXPECT_EQ(to_python(third), "1.0 / 3.0");
  EXPECT_EQ(to_latex(third), "\\frac{1}{3}");
  const Expression quarter_pi = alone(exact_constant(3, 4, Symbol::pi));
  EXPECT_EQ(to_infix(quarter_pi), "3 * pi / 4");
  EXPECT_EQ(to_cpp(quarter_pi), "3.0 * std::numbers::pi / 4.0");
  EXPECT_EQ(to_python(quarter_pi), "3.0 * math.pi / 4.0");
  EXPECT_EQ(to_latex(quarter_pi), "\\frac{3\\pi}{4}");
  EXPECT_EQ(to_glsl(quarter_pi), "3.0 * 3.1415927 / 4.0");
  EXPECT_EQ(to_infix(alone(exact_constant(1, 1, Symbol::e))), "exp(1)");
  EXPECT_EQ(to_infix(alone(exact_constant(1, 2, Symbol::one))), "0.5");
  EXPECT_EQ(to_cpp(alone(exact_constant(-3, 4, Symbol::one))), "-0.75");
  EXPECT_EQ(to_infix(alone(exact_constant(-1, 2, Symbol::sqrt3))), "-sqrt(3) / 2");
}

TEST(Exact, AnOperandIsParenthesizedAndReadsBackToTheSameValue) {
  for (const Node& c : {exact_constant(1, 3, Symbol::one), exact_constant(-1, 2, Symbol::one),
                        exact_constant(3, 4, Symbol::pi), exact_constant(-5, 7, Symbol::e)}) {
    const Expression e = times_x(c);
    const std::string text = to_infix(e);
    const Expression again = parse(text, {"x"});
    for (double x : {0.1, 1.0, 3.7, -2.5})
      EXPECT_EQ(evaluate(again, std::vector<double>{x}), evaluate(e, std::vector<double>{x})) << text;
  }
  EXPECT_EQ(to_infix(times_x(exact_constant(1, 3, Symbol::one))), "x * (1 / 3)");
  // Negative control: without the parentheses x * 1 / 3 is (x · 1)/3, another rounding.
  EXPECT_NE(evaluate(parse("x * 1 / 3", {"x"}), std::vector<double>{2.1}),
            evaluate(times_x(exact_constant(1, 3, Symbol::one)), std::vector<double>{2.1}));
}

TEST(Exact, PiParsesAsTheExactConstantUnlessAVariableIsCalledPi) {
  const Expression e = parse("pi / 2");
  EXPECT_TRUE(e.variables().empty());
  EXPECT_TRUE(is_exact(e.nodes()[0]));
  EXPECT_EQ(evaluate(e, {}), std::numbers::pi / 2);
  const Expression named = parse("pi / 2", {"pi"});
  EXPECT_EQ(named.nodes()[0].op, Op::variable);
}

TEST(Exact, SimplifyKeepsAnExactCoefficient) {
  EXPECT_EQ(to_infix(simplify(times_x(exact_constant(1, 3, Symbol::one)))), "1 / 3 * x");
  EXPECT_EQ(to_infix(simplify(times_x(exact_constant(-3, 4, Symbol::pi)))), "-3 * pi / 4 * x");
  // In a sum, a negative exact coefficient becomes a subtraction of its exact magnitude.
  const Node minus_third = exact_constant(-1, 3, Symbol::one);
  const Expression y_minus = Expression({Node{Op::variable, 1, 0}, Node{Op::variable, 0, 0}, minus_third,
                                         Node{Op::mul, 0, 0}, Node{Op::add, 0, 0}},
                                        {"x", "y"});
  EXPECT_EQ(to_infix(simplify(y_minus)), "y - 1 / 3 * x");
}

}  // namespace
}  // namespace specula::expr
