// Formulas read off the data by least squares over the monomials (src/fit/transformed.h).
#include "fit/transformed.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

namespace specula::fit {
namespace {

constexpr const char* kOperators = "+,-,*,/,sin,cos,exp,log,^";

struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  std::vector<double> target;

  Rows rows() const {
    Rows r;
    for (const auto& c : columns) r.columns.emplace_back(c);
    r.target = target;
    return r;
  }
};

// `truth` at n points drawn uniformly from [from, to] in each variable, times 1 + noise·N(0, 1).
Table drawn(const char* truth, std::vector<std::string> names, double from, double to, std::size_t n,
            double noise = 0) {
  const auto e = expr::parse(truth, names);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uniform(from, to);
  std::normal_distribution<double> normal;
  Table t{names, std::vector<std::vector<double>>(names.size()), {}};
  for (std::size_t r = 0; r < n; ++r) {
    std::vector<double> point;
    for (auto& column : t.columns) point.push_back(column.emplace_back(uniform(rng)));
    t.target.push_back(expr::evaluate(e, point) * (1 + noise * normal(rng)));
  }
  return t;
}

// The formulas found, their constants to 6 significant digits.
std::vector<std::string> found(const Table& t, const char* operators = kOperators) {
  std::vector<std::string> out;
  for (const Genome& g : transformed_polynomials(t.rows(), parse_operators(operators), SizeWeights()))
    out.push_back(expr::to_infix(rounded(expr::Expression(g, t.names), 6)));
  return out;
}

bool holds(const std::vector<std::string>& formulas, const std::string& formula) {
  return std::ranges::find(formulas, formula) != formulas.end();
}

TEST(TransformedPolynomials, ReadsARatioOfPolynomialsInItsSmallestScaling) {
  const Table t = drawn("8 / (2 + x ^ 2 + y ^ 2)", {"x", "y"}, -3, 3, 20);
  const auto formulas = found(t);
  EXPECT_TRUE(holds(formulas, "8 / (y ^ 2 + x ^ 2 + 2)")) << ::testing::PrintToString(formulas);
  // Keijzer-5: the monomial common to the denominator's terms, y², is multiplied out.
  const Table keijzer5 = drawn("30 * x * z / ((x - 10) * y ^ 2)", {"x", "y", "z"}, 1, 2, 200);
  EXPECT_TRUE(holds(found(keijzer5), "30 * x * z / ((x - 10) * y ^ 2)")) << ::testing::PrintToString(found(keijzer5));
  // Controls: without ÷ there is no ratio to write; with noise nothing fits to rounding.
  EXPECT_TRUE(found(t, "+,-,*,^").empty());
  EXPECT_TRUE(found(drawn("8 / (2 + x ^ 2 + y ^ 2)", {"x", "y"}, -3, 3, 20, 1e-6)).empty());
}

TEST(TransformedPolynomials, WritesUnitCoefficientsBareAndDropsRoundingTerms) {
  const Table t = drawn("x ^ 8 + x ^ 7 + x ^ 6 + x ^ 5 + x ^ 4 + x ^ 3 + x ^ 2 + x", {"x"}, -1, 1, 20);
  EXPECT_TRUE(holds(found(t), "x + x ^ 2 + x ^ 3 + x ^ 4 + x ^ 5 + x ^ 6 + x ^ 7 + x ^ 8"));
  const Table scaled = drawn("0.3 * (x - x ^ 3) + 2.5", {"x"}, -1, 1, 20);
  EXPECT_TRUE(holds(found(scaled), "0.3 * (x - x ^ 3 + 8.33333)")) << ::testing::PrintToString(found(scaled));
}

TEST(TransformedPolynomials, ReadsLogarithmsAndExponentialsOfPolynomials) {
  const Table logs = drawn("log(x + 1) + log(x ^ 2 + 1) + log(x)", {"x"}, 0.05, 2, 20);
  EXPECT_TRUE(holds(found(logs), "log(x + x ^ 2 + x ^ 3 + x ^ 4)")) << ::testing::PrintToString(found(logs));
  const Table gaussian = drawn("exp(-0.5 * x ^ 2 + x * y)", {"x", "y"}, -1, 1, 30);
  EXPECT_TRUE(holds(found(gaussian), "exp((y - 0.5 * x) * x)")) << ::testing::PrintToString(found(gaussian));
  EXPECT_TRUE(found(gaussian, "+,-,*,/,^").empty());  // control: no exp to write it with
}

TEST(TransformedPolynomials, NeverInterpolates) {
  // Nine monomials (degree 8) need 18 distinct points: 16 rows are not enough …
  EXPECT_TRUE(found(drawn("x ^ 8 + x", {"x"}, -1, 1, 16)).empty());
  // … nor 40 rows that repeat 6 points, where a quintic would pass through sin's values exactly.
  Table repeated{{"x"}, {{}}, {}};
  for (int r = 0; r < 40; ++r) {
    repeated.columns[0].push_back(r % 6);
    repeated.target.push_back(std::sin(r % 6));
  }
  EXPECT_TRUE(found(repeated).empty());
  EXPECT_FALSE(found(drawn("x ^ 8 + x", {"x"}, -1, 1, 18)).empty());  // control: 18 distinct points
}

}  // namespace
}  // namespace specula::fit
