// The Fresnel calls of a formula (expr.h: fresnel_call) against the built-in Fresnels of
// brdf/fresnel.h (themselves checked against mpmath in tests/analysis/fresnel_test.cpp).
#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <array>
#include <vector>

#include "specula/brdf/fresnel.h"
#include "specula/expr/expr.h"
#include "specula/expr/program.h"

namespace specula::expr {
namespace {

using ::testing::HasSubstr;

constexpr std::array kCosines{1e-3, 0.05, 0.2, 0.5, 0.8, 0.999, 1.0};

/// The formula at cosine c and the given parameter values (variables c, a, b, p in that order).
double at(const Expression& e, double c, double a, double b = 0, double p = 0) {
  const double values[] = {c, a, b, p};
  return evaluate(e, std::span<const double>(values, e.variables().size()));
}

TEST(FresnelCalls, EachKindIsTheBuiltinFresnel) {
  const Expression schlick = parse("fresnel_schlick(c, a)", {"c", "a"});
  const Expression schlick4 = parse("fresnel_schlick(c, a, b, p)", {"c", "a", "b", "p"});
  const Expression f82 = parse("fresnel_f82(c, a, b)", {"c", "a", "b"});
  const Expression dielectric = parse("fresnel_dielectric(c, a)", {"c", "a"});
  const Expression conductor = parse("fresnel_conductor(c, a, b)", {"c", "a", "b"});
  for (const double c : kCosines) {
    for (const double f0 : {0.0, 0.04, 0.5, 1.0}) {
      EXPECT_NEAR(at(schlick, c, f0), fresnel::schlick(c, f0), 1e-15) << c << " " << f0;
      EXPECT_NEAR(at(schlick4, c, f0, 0.7, 3.5), fresnel::schlick(c, f0, 0.7, 3.5), 1e-15) << c << " " << f0;
      for (const double tint : {0.0, 0.6, 1.0})
        EXPECT_NEAR(at(f82, c, f0, tint), fresnel::f82_tint(c, f0, fresnel::f82_tint_b(f0, tint)), 1e-14)
            << c << " " << f0 << " " << tint;
    }
    for (const double eta : {0.5, 0.9, 1.0, 1.5, 2.5, 40.0})  // below 1: total internal reflection
      EXPECT_NEAR(at(dielectric, c, eta), fresnel::dielectric(c, eta), 1e-13) << c << " " << eta;
    for (const auto& [eta, kappa] : std::array<std::pair<double, double>, 6>{
             {{0.2, 3.1}, {1.5, 0.0}, {0.66, 0.0}, {0.14, 3.98}, {2.8, 1.2}, {1.0, 10.0}}})
      EXPECT_NEAR(at(conductor, c, eta, kappa), fresnel::conductor(c, eta, kappa), 1e-12) << c << " " << eta << " " << kappa;
  }
}

TEST(FresnelCalls, ControlTheConductorWithExtinctionIsNotTheDielectric) {
  const Expression conductor = parse("fresnel_conductor(c, a, b)", {"c", "a", "b"});
  EXPECT_GT(std::abs(at(conductor, 0.5, 1.5, 0.5) - fresnel::dielectric(0.5, 1.5)), 1e-2);
}

TEST(FresnelCalls, ArgumentsAreAnyExpressionAndTheResultComposes) {
  const Expression e = parse("2 * fresnel_dielectric(x * x, 1 + y) + 1", {"x", "y"});
  const double values[] = {0.8, 0.5};
  EXPECT_NEAR(evaluate(e, values), 2 * fresnel::dielectric(0.64, 1.5) + 1, 1e-14);
  // It prints as the arithmetic it stands for, and reads back bit-identically.
  const Expression back = parse(to_infix(e), {"x", "y"});
  EXPECT_EQ(evaluate(back, values), evaluate(e, values));
}

TEST(FresnelCalls, AWrongArgumentCountNamesTheCall) {
  try {
    parse("fresnel_conductor(c, 1.5)");
    FAIL() << "parsed";
  } catch (const ParseError& e) {
    EXPECT_THAT(e.what(), HasSubstr("column 1"));
    EXPECT_THAT(e.what(), HasSubstr("'fresnel_conductor' takes 3 arguments but was given 2"));
  }
  EXPECT_THROW(parse("fresnel_schlick(c, 1, 2)"), ParseError);  // 2 or 4
  EXPECT_THROW(parse("fresnel_schlick + 1"), ParseError);        // a call needs its '('
}

TEST(FresnelCalls, TheirNamesAreReserved) {
  EXPECT_TRUE(is_reserved_call("fresnel_f82"));
  EXPECT_FALSE(is_reserved_call("fresnel"));
  EXPECT_THROW(Expression({Node{Op::variable, 0, 0}}, {"fresnel_dielectric"}), InvalidArgument);
  EXPECT_THROW(Program({"c"}, {"fresnel_conductor"}), InvalidArgument);
}

}  // namespace
}  // namespace specula::expr
