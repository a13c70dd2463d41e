// Polynomials recognised and multiplied out (src/fit/expanded.h).
#include "fit/expanded.h"

#include <gtest/gtest.h>

#include <cmath>

namespace specula::fit {
namespace {

std::optional<int> degree_of(std::string_view text) {
  const auto e = expr::parse(text, {"x", "y"});
  return polynomial_degree(Genome(e.nodes().begin(), e.nodes().end()));
}

TEST(PolynomialDegree, CountsTheDegreeOfProductsSumsAndIntegerPowers) {
  EXPECT_EQ(degree_of("4 * x * (x + 0.6) * ((x + 0.07) ^ 2 + 0.4)"), 4);
  EXPECT_EQ(degree_of("x * y - (y ^ 3) / 2.5"), 3);
  EXPECT_EQ(degree_of("-(x + 1) * sqrt(2)"), 1);
  EXPECT_EQ(degree_of("3"), 0);
}

TEST(PolynomialDegree, NoneForWhatNoPolynomialWrites) {
  EXPECT_FALSE(degree_of("x ^ 2.5"));  // not an integer power
  EXPECT_FALSE(degree_of("1 / x"));
  EXPECT_FALSE(degree_of("x ^ 2 + sin(y)"));
  EXPECT_FALSE(degree_of("(x + 1) ^ y"));
  EXPECT_TRUE(degree_of("x ^ 2 + sin(2)"));  // control: a function of a constant is a constant
}

TEST(DensePolynomial, HoldsEveryMonomialOnce) {
  EXPECT_EQ(monomial_count(4, 1), 5u);
  EXPECT_EQ(monomial_count(3, 2), 10u);
  EXPECT_EQ(monomial_count(2, 3), 10u);
  const Genome g = dense_polynomial(3, 2);
  EXPECT_EQ(std::count_if(g.begin(), g.end(), is_free_constant), 10);
  EXPECT_EQ(polynomial_degree(g), 3);
  // With every coefficient 1, at (x, y) = (2, 3): Σ over i + j ≤ 3 of 2^i·3^j.
  double expected = 0;
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; i + j <= 3; ++j) expected += std::pow(2, i) * std::pow(3, j);
  EXPECT_DOUBLE_EQ(expr::evaluate(expr::Expression(g, {"x", "y"}), std::vector<double>{2, 3}), expected);
}

}  // namespace
}  // namespace specula::fit
