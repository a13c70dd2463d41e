// Postfix edits and canonical keys of the symbolic-regression search.
#include "fit/genome.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "expr/random_expression.h"

namespace specula::fit {
namespace {

Genome nodes_of(std::string_view text) {
  const auto e = expr::parse(text, {"x", "y"});
  return {e.nodes().begin(), e.nodes().end()};
}

std::string key(std::string_view text) { return canonical_key(nodes_of(text)); }

TEST(SubtreeStarts, PointToTheFirstNodeOfEachSubtree) {
  // x 2 * y sin +  →  (x*2) + sin(y)
  const Genome g = nodes_of("x * 2 + sin(y)");
  EXPECT_EQ(subtree_starts(g), (std::vector<std::size_t>{0, 1, 0, 3, 3, 0}));
}

TEST(Replaced, SplicesASubtree) {
  const Genome g = nodes_of("x * 2 + sin(y)");
  const Genome y = nodes_of("y");
  const Genome out = replaced(g, 0, 2, y);  // x*2 → y
  EXPECT_EQ(expr::to_infix(expr::Expression(out, {"x", "y"})), "y + sin(y)");
}

TEST(CanonicalKey, IgnoresConstantValuesOrderAndGrouping) {
  EXPECT_EQ(key("2*x + 3"), key("1 + x*5"));
  EXPECT_EQ(key("(x + 1) + 2"), key("x + 7"));
  EXPECT_EQ(key("x / 4"), key("0.5 * x"));
  EXPECT_EQ(key("x - 3"), key("x + 3"));
  EXPECT_EQ(key("(x*y)*2"), key("y*(2*x)"));
  EXPECT_EQ(key("sin(2 + 3) * x"), key("x * 7"));
  EXPECT_EQ(key("x*y + y"), key("y + y*x"));
}

TEST(CanonicalKey, KeepsDifferentFormsApart) {
  EXPECT_NE(key("x + y"), key("x * y"));
  EXPECT_NE(key("2 / x"), key("x / 2"));
  EXPECT_NE(key("x - y"), key("y - x"));
  EXPECT_NE(key("(x + 1) * y"), key("x * y + 1"));
  EXPECT_NE(key("x"), key("y"));
}

// An exact constant is not free: x^2 (exact) and x^c are different forms, x^2 and x^3 too.
TEST(CanonicalKey, KeysExactConstantsByTheirValue) {
  const auto power = [](expr::Node exponent) {
    return canonical_key(Genome{{expr::Op::variable, 0, 0}, exponent, {expr::Op::pow, 0, 0}});
  };
  const auto two = expr::exact_constant(2, 1, expr::Symbol::one);
  EXPECT_EQ(power(two), power(two));
  EXPECT_NE(power(two), key("x ^ 2"));
  EXPECT_NE(power(two), power(expr::exact_constant(3, 1, expr::Symbol::one)));
  EXPECT_EQ(key("x ^ 2"), key("x ^ 3"));  // negative control: free exponents share a key
}

TEST(FoldedConstants, CollapsesConstantOnlySubtrees) {
  const auto folded = [](std::string_view text) {
    return expr::to_infix(expr::Expression(folded_constants(nodes_of(text)), {"x", "y"}));
  };
  EXPECT_EQ(folded("x + (2 * 3 - 1)"), "x + 5");
  EXPECT_EQ(folded("sin(0) * x + exp(0)"), "0 * x + 1");
  EXPECT_EQ(folded("x * log(0 - 1)"), "x * log(-1)");  // nan stays unfolded
  EXPECT_EQ(folded("x / y"), "x / y");
}

Alphabet test_alphabet(int max_size, Constants constants = Constants::fitted) {
  Options o;
  o.operators = {expr::Op::add, expr::Op::sub, expr::Op::mul, expr::Op::div, expr::Op::sin,
                 expr::Op::exp};
  o.max_size = max_size;
  o.constants = constants;
  return Alphabet(o, 2);
}

// Every edit keeps a well-formed formula (the Expression constructor checks) within the limit.
RC_GTEST_PROP(Variation, KeepsFormulasWellFormedAndWithinTheSizeLimit, (std::uint64_t seed)) {
  const Alphabet a = test_alphabet(15);
  Rng rng(seed);
  Genome x = a.random_tree(rng, 9), y = a.random_tree(rng, 12);
  RC_ASSERT(a.fits(x));
  RC_ASSERT(a.fits(y));
  for (int i = 0; i < 20; ++i) {
    x = i % 2 ? crossover(x, y, a, rng) : mutate(x, a, rng);
    RC_ASSERT(a.fits(x));
    expr::Expression checked(x, {"x", "y"});
    RC_ASSERT(checked.size() == x.size());
  }
}

RC_GTEST_PROP(Variation, UsesOnlyTheAlphabet, (std::uint64_t seed)) {
  const Alphabet a = test_alphabet(12, Constants::none);
  Rng rng(seed);
  Genome x = a.random_tree(rng, 12);
  for (int i = 0; i < 10; ++i) x = mutate(crossover(x, a.random_tree(rng, 7), a, rng), a, rng);
  for (const auto& n : x) {
    RC_ASSERT(n.op != expr::Op::constant);
    RC_ASSERT(n.op != expr::Op::pow);
  }
}

// Subtree starts agree with the printer: the subtree rooted at each node is itself well formed.
RC_GTEST_PROP(SubtreeStarts, DelimitWellFormedSubtrees, ()) {
  const auto e = *expr::testing::random_expression();
  const auto starts = subtree_starts(e.nodes());
  for (std::size_t i = 0; i < e.size(); ++i) {
    std::vector<expr::Node> sub(e.nodes().begin() + static_cast<std::ptrdiff_t>(starts[i]),
                                e.nodes().begin() + static_cast<std::ptrdiff_t>(i) + 1);
    expr::Expression checked(std::move(sub), {"x", "y"});
    RC_ASSERT(checked.size() == i - starts[i] + 1);
  }
}

}  // namespace
}  // namespace specula::fit
