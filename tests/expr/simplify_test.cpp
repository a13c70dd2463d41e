// specula::expr::simplify (include/specula/expr/simplify.h): each rewrite the docs list, the
// canonical order that makes two spellings of one formula the same, and agrees_on's check.
#include "specula/expr/simplify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

std::string simplified(const std::string& text) { return to_infix(simplify(parse(text, {"x", "y"}))); }

TEST(Simplify, RemovesWhatCancels) {
  EXPECT_EQ(simplified("x - x"), "0");
  EXPECT_EQ(simplified("x / x"), "1");
  EXPECT_EQ(simplified("x * 1"), "x");
  EXPECT_EQ(simplified("x + 0"), "x");
  EXPECT_EQ(simplified("-(-x)"), "x");
  EXPECT_EQ(simplified("(x * y) / x"), "y");
}

TEST(Simplify, FoldsConstants) {
  EXPECT_EQ(simplified("2 * 3 + x"), "x + 6");
  EXPECT_EQ(simplified("x * 2 * 4"), "8 * x");
  EXPECT_EQ(simplified("exp(0) * x"), "x");
}

TEST(Simplify, CollectsLikeTermsAndMergesPowers) {
  EXPECT_EQ(simplified("x + 2 * x"), "3 * x");
  EXPECT_EQ(simplified("x * x"), "x ^ 2");
  EXPECT_EQ(simplified("x * x * x / x"), "x ^ 2");
  EXPECT_EQ(simplified("sqrt(x) * sqrt(x)"), "x");
  EXPECT_EQ(simplified("x ^ 2 * x ^ -0.5"), "x ^ 1.5");
}

TEST(Simplify, WritesSubtractionAndDivisionBack) {
  EXPECT_EQ(simplified("x + -1 * y"), "x - y");
  EXPECT_EQ(simplified("x + -2 * y"), "x - 2 * y");
  EXPECT_EQ(simplified("x * y ^ -1"), "x / y");
  EXPECT_EQ(simplified("-1 + x"), "x - 1");
}

TEST(Simplify, TwoSpellingsOfOneFormulaBecomeOne) {
  EXPECT_EQ(simplified("y * x + 1"), simplified("1 + x * y"));
  EXPECT_EQ(simplified("(x + y) * 2"), simplified("2 * (y + x)"));
  EXPECT_EQ(simplified("x - (y - x)"), simplified("2 * x - y"));
  // Negative control: different formulas stay different.
  EXPECT_NE(simplified("x - y"), simplified("y - x"));
}

TEST(Simplify, ThePapersBloatedFormReadsAsAProduct) {
  const Expression e = parse("(9.424777960769376 + x) * 0.3333333333333334 * x", {"x"});
  const Expression s = simplify(e);
  EXPECT_LE(s.size(), e.size());
  EXPECT_EQ(to_infix(s), "0.3333333333333334 * x * (x + 9.424777960769376)");
}

TEST(Simplify, IsAFixedPoint) {
  for (const char* text : {"x * x + 2 * x * x", "(x + 1) / (x + 1) * y", "sqrt(x * x) + x - x", "-(x - y) - (y - x)"}) {
    const Expression once = simplify(parse(text, {"x", "y"}));
    EXPECT_EQ(to_infix(simplify(once)), to_infix(once)) << text;
  }
}

TEST(Simplify, KeepsAFormulaWhoseConstantsWouldOverflow) {
  const Expression e = parse("1e300 * 1e300 * x", {"x"});
  EXPECT_EQ(to_infix(simplify(e)), to_infix(e));
}

TEST(AgreesOn, TellsAnEqualRewriteFromADomainChange) {
  const std::vector<double> xs{-2, -0.5, 0.25, 1, 3};
  const std::vector<std::span<const double>> columns{xs};
  const Expression x = parse("x", {"x"});
  EXPECT_TRUE(agrees_on(parse("x * x / x", {"x"}), x, columns));
  // √x·√x is x only where x ≥ 0: the negative rows tell them apart.
  EXPECT_FALSE(agrees_on(parse("sqrt(x) * sqrt(x)", {"x"}), x, columns));
  const std::vector<double> zero{0, 1};
  const std::vector<std::span<const double>> at_zero{zero};
  EXPECT_FALSE(agrees_on(parse("x / x", {"x"}), parse("1", {"x"}), at_zero));
}

}  // namespace
}  // namespace specula::expr
