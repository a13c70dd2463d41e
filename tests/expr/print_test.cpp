// specula::expr printers (include/specula/expr/expr.h): exact text in every dialect, minimal
// parentheses, and the round-trip properties of to_infix over random expressions.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "expr/random_expression.h"
#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

std::string infix(const std::string& text) { return to_infix(parse(text)); }

// ---- infix ----------------------------------------------------------------------------------

TEST(ToInfix, CanonicalSpacingAndNumbers) {
  EXPECT_EQ(infix("x+2*y"), "x + 2 * y");
  EXPECT_EQ(infix("1.50e1 + .5 + 1e-3 + 2.5E+7 + 1e21"), "15 + 0.5 + 0.001 + 25000000 + 1e+21");
  EXPECT_EQ(infix("0.1"), "0.1");
  EXPECT_EQ(infix("pow(x, 2)"), "x ^ 2");
}

// Inside an elementary constant (an op over exact constants only) exact decimals print as the
// fractions they are, so that a CAS reads exp(-1 / 2) exactly; elsewhere a half stays 0.5 (the
// control: x ^ 0.5 and 0.5 * x).
TEST(ToInfix, ElementaryConstantsWriteTheirDecimalsAsFractions) {
  const Node minus_half = exact_constant(-1, 2, Symbol::one), half = exact_constant(1, 2, Symbol::one);
  const Node three_halves = exact_constant(3, 2, Symbol::one);
  EXPECT_EQ(to_infix(Expression({minus_half, {Op::exp}}, {})), "exp(-1 / 2)");
  EXPECT_EQ(to_infix(Expression({three_halves, half, {Op::pow}}, {})), "(3 / 2) ^ (1 / 2)");
  EXPECT_EQ(to_infix(Expression({minus_half, {Op::exp}, {Op::variable, 0, 0}, {Op::pow}}, {"x"})), "exp(-1 / 2) ^ x");
  EXPECT_EQ(to_infix(Expression({{Op::variable, 0, 0}, half, {Op::pow}}, {"x"})), "x ^ 0.5");
  EXPECT_EQ(to_infix(Expression({half, {Op::variable, 0, 0}, {Op::mul}}, {"x"})), "0.5 * x");
}

TEST(ToInfix, MinimalParentheses) {
  EXPECT_EQ(infix("(x * y) + z"), "x * y + z");
  EXPECT_EQ(infix("(x + y) * z"), "(x + y) * z");
  EXPECT_EQ(infix("x - (y - z)"), "x - (y - z)");
  EXPECT_EQ(infix("(x - y) - z"), "x - y - z");
  EXPECT_EQ(infix("x + (y + z)"), "x + (y + z)");
  EXPECT_EQ(infix("x / (y * z)"), "x / (y * z)");
  EXPECT_EQ(infix("x ^ (y ^ z)"), "x ^ y ^ z");
  EXPECT_EQ(infix("(x ^ y) ^ z"), "(x ^ y) ^ z");
  EXPECT_EQ(infix("-(x ^ 2)"), "-x ^ 2");
  EXPECT_EQ(infix("(-x) ^ 2"), "(-x) ^ 2");
  EXPECT_EQ(infix("x ^ (-y)"), "x ^ -y");
  EXPECT_EQ(infix("x * (-y)"), "x * -y");
  EXPECT_EQ(infix("-(x * y)"), "-(x * y)");
  EXPECT_EQ(infix("-(-x)"), "- -x");  // not -(-x): that nests deeper than the --x it may come from
  EXPECT_EQ(infix("--x"), "- -x");
  EXPECT_EQ(infix("log((x + 1))"), "log(x + 1)");
  EXPECT_EQ(infix("max(x, y) - min(1, y)"), "max(x, y) - min(1, y)");
}

// Found by fuzz/expr_fuzz.cpp (fuzz/corpus/expr/nesting_limit_negation): 999 signs printed as
// -(-(-…)) nested twice as deep as parse() allows.
TEST(ToInfix, ReadsBackAtTheNestingLimit) {
  const int signs = kMaxNesting - 1;
  for (const std::string& text : {std::string(signs, '-') + "x", "x ^ " + std::string(signs - 1, '-') + "y"}) {
    const Expression e = parse(text);
    Expression again = e;
    ASSERT_NO_THROW(again = parse(to_infix(e))) << text.substr(0, 20);
    EXPECT_EQ(to_infix(again), to_infix(e));
    EXPECT_EQ(evaluate(again, std::vector<double>{2, 3}), evaluate(e, std::vector<double>{2, 3}));
  }
}

TEST(ToInfix, NegativeConstants) {
  const Expression e({{Op::constant, 0, -2.0}, {Op::variable, 0, 0}, {Op::pow, 0, 0}}, {"x"});
  EXPECT_EQ(to_infix(e), "(-2) ^ x");
  const Expression zero({{Op::constant, 0, -0.0}}, {});
  EXPECT_EQ(to_infix(zero), "-0");
  EXPECT_TRUE(std::signbit(evaluate(parse(to_infix(zero)), {})));
}

// Every number to_infix writes reads back as the same bits: the designer writes its lobes' formulas
// (design.json, models.toml) with it, and a subnormal constant there once ended a run with
// "internal error: stod" (fit::rounded, tests/design/merge_test.cpp).
TEST(ToInfix, NumbersAtTheEndsOfTheDoublesReadBack) {
  constexpr double kMax = std::numeric_limits<double>::max(), kTiny = std::numeric_limits<double>::denorm_min();
  for (const double v : {0.0, -0.0, kTiny, -kTiny, 1e-320, 2.5e-310, std::numeric_limits<double>::min(), kMax, -kMax,
                         0.1, 1e21, 123456789.125}) {
    const Expression constant({{Op::constant, 0, v}}, {});
    const std::string text = to_infix(constant);
    const double back = evaluate(parse(text), {});
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(v)) << text;
    const Expression product = parse("c * " + text);  // as a constant of a lobe
    EXPECT_EQ(to_infix(parse(to_infix(product))), to_infix(product)) << text;
  }
  // The control: a number past the largest double is refused, not read as inf.
  EXPECT_THROW(parse("1.8e308"), ParseError);
}

// ---- other dialects -------------------------------------------------------------------------

TEST(ToCpp, ExactText) {
  EXPECT_EQ(to_cpp(parse("0.5*x^2")), "0.5 * std::pow(x, 2.0)");
  EXPECT_EQ(to_cpp(parse("-(-x) + log2(y) / 1e-5")), "-(-x) + std::log2(y) / 1e-05");
  EXPECT_EQ(to_cpp(parse("max(abs(x), sqrt(y)) - acos(cos(sin(exp(3))))")),
            "std::max(std::abs(x), std::sqrt(y)) - std::acos(std::cos(std::sin(std::exp(3.0))))");
  EXPECT_EQ(to_cpp(parse("(-x)^-2")), "std::pow(-x, -2.0)");
}

// GLSL's pow(x, y) is undefined for x < 0 (NaN on GPUs): a whole power is written so that it is
// defined for every x; any other power stays pow (the control).
TEST(ToGlsl, WholePowersAreDefinedForNegativeBases) {
  EXPECT_EQ(to_glsl(parse("0.5*x^2")), "0.5 * pow(abs(x), 2.0)");
  EXPECT_EQ(to_glsl(parse("(x - 1)^3")), "(x - 1.0) * pow(abs(x - 1.0), 2.0)");
  EXPECT_EQ(to_glsl(parse("x^-2")), "pow(abs(x), -2.0)");
  EXPECT_EQ(to_glsl(parse("x^2.5")), "pow(x, 2.5)");
  EXPECT_EQ(to_glsl(parse("x^y")), "pow(x, y)");
}

TEST(ToGlsl, FloatLiterals) {
  EXPECT_EQ(to_glsl(parse("0.1 + 1e-5 + 3e20")), "0.1 + 1.0e-05 + 3.0e+20");
  EXPECT_EQ(to_glsl(parse("min(log(x), max(-y, acos(1)))")), "min(log(x), max(-y, acos(1.0)))");
  EXPECT_EQ(to_glsl(parse("-(-x)")), "-(-x)");
}

TEST(ToLatex, ExactText) {
  EXPECT_EQ(to_latex(parse("x / (y + 1)")), "\\frac{x}{y + 1}");
  EXPECT_EQ(to_latex(parse("2 * x ^ (y + 1)")), "2 \\cdot x^{y + 1}");
  EXPECT_EQ(to_latex(parse("(x + 1) ^ 2")), "\\left(x + 1\\right)^{2}");
  EXPECT_EQ(to_latex(parse("sqrt(x) ^ 2")), "\\left(\\sqrt{x}\\right)^{2}");
  EXPECT_EQ(to_latex(parse("log(x) + log2(y) + abs(x)")),
            "\\log\\left(x\\right) + \\log_2\\left(y\\right) + \\left|x\\right|");
  EXPECT_EQ(to_latex(parse("acos(x) * min(x, y) * 1e-5")),
            "\\arccos\\left(x\\right) \\cdot \\min\\left(x, y\\right) \\cdot (1 \\cdot 10^{-5})");
}

TEST(ToPython, ExactText) {
  EXPECT_EQ(to_python(parse("0.5*x^2")), "0.5 * x ** 2.0");
  EXPECT_EQ(to_python(parse("-2^-x ^ y")), "-2.0 ** -x ** y");
  EXPECT_EQ(to_python(parse("(x ^ y) ^ 2")), "(x ** y) ** 2.0");
  EXPECT_EQ(to_python(parse("log(x) + log2(x) + exp(x) + sqrt(x) + abs(x)")),
            "math.log(x) + math.log2(x) + math.exp(x) + math.sqrt(x) + abs(x)");
  EXPECT_EQ(to_python(parse("min(sin(x), max(cos(x), acos(x)))")),
            "min(math.sin(x), max(math.cos(x), math.acos(x)))");
}

// ---- round trips ----------------------------------------------------------------------------

bool printed_bits_or_both_nan(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) ||
         std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

RC_GTEST_PROP(ToInfix, ReparsingEvaluatesBitIdentically, ()) {
  const Expression e = *testing::random_expression();
  const Expression reparsed = parse(to_infix(e), e.variables());
  const auto x =
      *rc::gen::suchThat(rc::gen::arbitrary<double>(), [](double v) { return std::isfinite(v); });
  const auto y = *rc::gen::element(0.0, -1.0, 0.5, 2.0, 1e-3, 7.25);
  const std::vector<double> point{x, y};
  RC_ASSERT(printed_bits_or_both_nan(evaluate(reparsed, point), evaluate(e, point)));
}

RC_GTEST_PROP(ToInfix, IsAFixedPointAfterOneRound, ()) {
  const Expression e = *testing::random_expression();
  const std::string once = to_infix(e);
  RC_ASSERT(to_infix(parse(once, e.variables())) == once);
}

}  // namespace
}  // namespace specula::expr
