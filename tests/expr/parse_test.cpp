// specula::expr::parse (include/specula/expr/expr.h): accepted syntax, precedence and
// associativity against hand-computed values, variables, and every rejection with its column.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "specula/exceptions.h"
#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

double value_of(const std::string& text, std::vector<double> variables = {}) {
  return evaluate(parse(text), variables);
}

// The message of the ParseError that parse(text, variables) throws ("" if it throws none).
std::string error_of(const std::string& text, std::vector<std::string> variables = {}) {
  try {
    (void)parse(text, std::move(variables));
  } catch (const ParseError& e) {
    return e.what();
  }
  return "";
}

// ---- accepted syntax ------------------------------------------------------------------------

TEST(Parse, Numbers) {
  EXPECT_EQ(value_of("2"), 2.0);
  EXPECT_EQ(value_of("0.25"), 0.25);
  EXPECT_EQ(value_of(".5"), 0.5);
  EXPECT_EQ(value_of("5."), 5.0);
  EXPECT_EQ(value_of("1e-3"), 1e-3);
  EXPECT_EQ(value_of("2.5E+7"), 2.5e7);
}

TEST(Parse, SubnormalNumbersReadExactly) {
  EXPECT_EQ(value_of("5e-324"), 5e-324);
  EXPECT_EQ(value_of("1e-400"), 0.0);
}

TEST(Parse, Whitespace) { EXPECT_EQ(value_of(" \t1 +\n2 "), 3.0); }

TEST(Parse, NodesArePostfix) {
  const Expression e = parse("x + 2 * y");
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(e.nodes()[0].op, Op::variable);
  EXPECT_EQ(e.nodes()[1].op, Op::constant);
  EXPECT_EQ(e.nodes()[2].op, Op::variable);
  EXPECT_EQ(e.nodes()[3].op, Op::mul);
  EXPECT_EQ(e.nodes()[4].op, Op::add);
  EXPECT_EQ(e.stack_depth(), 3u);
}

TEST(Parse, VariablesInOrderOfFirstUse) {
  EXPECT_THAT(parse("b * a + b_2 - a").variables(), ElementsAre("b", "a", "b_2"));
}

TEST(Parse, GivenVariablesKeepTheirOrder) {
  const Expression e = parse("y - x", {"x", "y", "unused"});
  EXPECT_THAT(e.variables(), ElementsAre("x", "y", "unused"));
  EXPECT_EQ(evaluate(e, std::vector{1.0, 10.0, 100.0}), 9.0);
}

// ---- precedence and associativity -----------------------------------------------------------

TEST(Parse, Precedence) {
  EXPECT_EQ(value_of("1 + 2 * 3"), 7.0);
  EXPECT_EQ(value_of("(1 + 2) * 3"), 9.0);
  EXPECT_EQ(value_of("2 * 3 ^ 2"), 18.0);
  EXPECT_EQ(value_of("-2 ^ 2"), -4.0);
  EXPECT_EQ(value_of("(-2) ^ 2"), 4.0);
  EXPECT_EQ(value_of("2 ^ -1"), 0.5);
  EXPECT_EQ(value_of("-2 * 3"), -6.0);
  EXPECT_EQ(value_of("1 - -2"), 3.0);
  EXPECT_EQ(value_of("--3"), 3.0);
  EXPECT_EQ(value_of("6 / -2 ^ 2"), -1.5);
}

TEST(Parse, Associativity) {
  EXPECT_EQ(value_of("10 - 4 - 3"), 3.0);
  EXPECT_EQ(value_of("64 / 4 / 2"), 8.0);
  EXPECT_EQ(value_of("2 ^ 3 ^ 2"), 512.0);
  EXPECT_EQ(value_of("(2 ^ 3) ^ 2"), 64.0);
  EXPECT_EQ(value_of("2 ^ -1 ^ 2"), 0.5);  // 2^(-(1^2))
  EXPECT_EQ(value_of("8 / 2 * 4"), 16.0);
}

TEST(Parse, EveryFunction) {
  EXPECT_EQ(value_of("log(1)"), 0.0);
  EXPECT_EQ(value_of("log2(8)"), 3.0);
  EXPECT_EQ(value_of("exp(0)"), 1.0);
  EXPECT_EQ(value_of("sqrt(16)"), 4.0);
  EXPECT_EQ(value_of("abs(-3)"), 3.0);
  EXPECT_EQ(value_of("sin(0)"), 0.0);
  EXPECT_EQ(value_of("cos(0)"), 1.0);
  EXPECT_EQ(value_of("acos(1)"), 0.0);
  EXPECT_EQ(value_of("pow(2, 10)"), 1024.0);
  EXPECT_EQ(value_of("min(3, -1)"), -1.0);
  EXPECT_EQ(value_of("max(3, -1)"), 3.0);
  EXPECT_EQ(value_of("max(1 + 1, min(4, 5) * 2) - log(exp(2))"), 6.0);
}

// ---- rejections -----------------------------------------------------------------------------

TEST(Parse, EmptyInput) {
  EXPECT_EQ(
      error_of(""),
      "column 1: expected a number, a variable, a function call or '(' but found end of input");
  EXPECT_EQ(
      error_of("   "),
      "column 4: expected a number, a variable, a function call or '(' but found end of input");
}

TEST(Parse, MissingOperand) {
  EXPECT_EQ(
      error_of("1 +"),
      "column 4: expected a number, a variable, a function call or '(' but found end of input");
  EXPECT_EQ(error_of("1 * * 2"),
            "column 5: expected a number, a variable, a function call or '(' but found '*'");
  EXPECT_EQ(error_of("()"),
            "column 2: expected a number, a variable, a function call or '(' but found ')'");
}

TEST(Parse, UnbalancedParentheses) {
  EXPECT_EQ(error_of("(1 + 2"), "column 7: expected ')' but found end of input");
  EXPECT_EQ(error_of("(1 + 2))"), "column 8: expected an operator or end of input but found ')'");
}

TEST(Parse, TrailingGarbage) {
  EXPECT_EQ(error_of("2 x"), "column 3: expected an operator or end of input but found 'x'");
  EXPECT_EQ(error_of("2e"), "column 2: expected an operator or end of input but found 'e'");
  EXPECT_EQ(error_of("1.5.3"),
            "column 4: expected an operator or end of input but found number '.3'");
}

TEST(Parse, UnexpectedCharacter) {
  EXPECT_EQ(error_of("1 + #"), "column 5: unexpected character '#'");
  EXPECT_EQ(error_of("1 + ."), "column 5: expected a digit before or after '.'");
}

TEST(Parse, NumberOutOfRange) {
  EXPECT_EQ(error_of("x + 1e400"), "column 5: number '1e400' is out of range");
  EXPECT_EQ(error_of("1e400 * 0"), "column 1: number '1e400' is out of range");
}

TEST(Parse, UnknownFunction) {
  EXPECT_EQ(error_of("1 + foo(2)"), "column 5: unknown function 'foo'");
}

TEST(Parse, FunctionNamesAreReserved) {
  EXPECT_EQ(error_of("log + 1"), "column 5: expected '(' after 'log' but found '+'");
}

TEST(Parse, WrongArity) {
  EXPECT_EQ(error_of("2 * pow(2)"), "column 5: 'pow' takes 2 arguments but was given 1");
  EXPECT_EQ(error_of("sqrt(1, 2)"), "column 1: 'sqrt' takes 1 argument but was given 2");
  EXPECT_EQ(error_of("min(1 2)"), "column 7: expected ',' or ')' but found number '2'");
}

TEST(Parse, UnknownVariable) {
  EXPECT_EQ(error_of("x + z", {"x", "y"}),
            "column 5: unknown variable 'z' (the variables are x, y)");
}

TEST(Parse, NestingIsBounded) {
  EXPECT_EQ(value_of(std::string(500, '(') + "1" + std::string(500, ')')), 1.0);
  EXPECT_THAT(error_of(std::string(2000, '-') + "1"), HasSubstr("nests deeper than 1000 levels"));
}

TEST(Parse, ParseErrorIsAnInvalidArgument) { EXPECT_THROW((void)parse(")"), InvalidArgument); }

// ---- Expression invariants ------------------------------------------------------------------

TEST(Expression, RejectsMalformedPostfix) {
  EXPECT_THROW(Expression({}, {}), InvalidArgument);
  EXPECT_THROW(Expression({{Op::add, 0, 0}}, {}), InvalidArgument);
  EXPECT_THROW(Expression({{Op::constant, 0, 1}, {Op::constant, 0, 2}}, {}), InvalidArgument);
  EXPECT_THROW(Expression({{Op::variable, 1, 0}}, {"x"}), InvalidArgument);
  EXPECT_THROW(Expression({{Op::constant, 0, INFINITY}}, {}), InvalidArgument);
}

TEST(Expression, RejectsBadVariableNames) {
  const std::vector<Node> x{{Op::variable, 0, 0}};
  EXPECT_THROW(Expression(x, {"1x"}), InvalidArgument);
  EXPECT_THROW(Expression(x, {"log"}), InvalidArgument);
  EXPECT_THROW(Expression(x, {"x", "x"}), InvalidArgument);
  EXPECT_THROW((void)parse("x", {"x", "x"}), InvalidArgument);
}

}  // namespace
}  // namespace specula::expr
