#include <gtest/gtest.h>
#include <algorithm>
#include <set>
#include <span>

#include "design/shapes.h"

namespace specula::design {
namespace {

TEST(Shapes, EnumerationIsByCostWithoutRepeats) {
  const auto shapes = enumerate_shapes(parse_operations("all"), 6, 1'000'000);
  std::set<std::string> keys;
  int cost = 0;
  for (const auto& s : shapes) {
    EXPECT_TRUE(keys.insert(s.key).second) << s.key;
    EXPECT_GE(s.cost, cost);
    EXPECT_LE(s.cost, 6);
    EXPECT_LE(s.constants, kMaxShapeConstants);
    cost = s.cost;
  }
  EXPECT_TRUE(keys.count("c"));
  EXPECT_TRUE(keys.count("max(c * 7 + 7, 0) ^ 2")) << "the clamped affine square";
  EXPECT_TRUE(keys.count("c / (c * 7 + 7)")) << "Schlick's rational shape";
}

// a·x + b·y joins two computed features (no free constants of their own): a linear model in them.
TEST(Shapes, CombinationsJoinFeaturesWithoutConstants) {
  const auto shapes = enumerate_shapes(parse_operations("all"), 5, 1'000'000);
  int combinations = 0;
  for (const auto& s : shapes)
    if (s.step == Shape::Step::combination) {
      ++combinations;
      EXPECT_EQ(s.constants, 2) << s.key;
    }
  EXPECT_GT(combinations, 10);
  EXPECT_TRUE(std::ranges::any_of(shapes, [](const Shape& s) { return s.key == "c * 7 + c ^ 2 * 7"; }));
  // Without fma or without mul there is no combination.
  for (const char* ops : {"mul,add,max", "fma,add,max"})
    for (const auto& s : enumerate_shapes(parse_operations(ops), 6, 1'000'000)) EXPECT_NE(s.step, Shape::Step::combination) << ops;
}

TEST(Shapes, OperationsRestrictTheSpace) {
  for (const auto& s : enumerate_shapes(parse_operations("fma,max"), 8, 1'000'000)) {
    EXPECT_EQ(s.key.find('^'), std::string::npos) << s.key;
    EXPECT_EQ(s.key.find('/'), std::string::npos) << s.key;
  }
  EXPECT_GT(enumerate_shapes(parse_operations("all"), 8, 1'000'000).size(),
            enumerate_shapes(parse_operations("fma,max"), 8, 1'000'000).size());
}

// A clamp max(x, 0) of what is ≥ 0 already, or √(x²), gives back a cheaper shape.
bool clamp_of_clamp(std::span<const expr::Node> n, std::size_t i) {
  const auto zero_clamp = [&](std::size_t k) {
    return k >= 1 && n[k].op == expr::Op::max && expr::is_exact(n[k - 1]) && n[k - 1].value == 0;
  };
  return zero_clamp(i) && i >= 2 && zero_clamp(i - 2);
}
bool root_of_square(std::span<const expr::Node> n, std::size_t i) {
  return n[i].op == expr::Op::sqrt && i >= 2 && n[i - 1].op == expr::Op::pow && n[i - 2].value == 2;
}

TEST(Shapes, RedundantStepsAreNotTaken) {
  for (const auto& s : enumerate_shapes(parse_operations("all"), 7, 1'000'000))
    for (std::size_t i = 0; i < s.nodes.size(); ++i) {
      EXPECT_FALSE(clamp_of_clamp(s.nodes, i)) << s.key;
      EXPECT_FALSE(root_of_square(s.nodes, i)) << s.key;
    }
}

TEST(Shapes, TheRedundancyChecksSeeRedundancy) {  // the negative control of the test above
  const auto nodes = [](const char* text) {
    const auto e = expr::parse(text, {"c"});
    return std::vector<expr::Node>(e.nodes().begin(), e.nodes().end());
  };
  auto twice = nodes("max(max(c, 0), 0)");
  for (auto& n : twice)
    if (n.op == expr::Op::constant) n = expr::exact_constant(0, 1, expr::Symbol::one);
  EXPECT_TRUE(clamp_of_clamp(twice, twice.size() - 1));
  auto root = nodes("sqrt(c ^ 2)");
  EXPECT_TRUE(root_of_square(root, root.size() - 1));
}

TEST(Shapes, TheLimitIsHeld) { EXPECT_EQ(enumerate_shapes(parse_operations("all"), 12, 50).size(), 50u); }

TEST(Shapes, ALimitIsAPrefixOfTheWholeOrder) {  // what makes --max-forms one budget for all shards
  const auto ops = parse_operations("fma,mul,max,div");
  const auto whole = enumerate_shapes(ops, 6, 1'000'000);
  const auto first = enumerate_shapes(ops, 6, 300);
  ASSERT_GT(whole.size(), first.size());
  for (std::size_t i = 0; i < first.size(); ++i) EXPECT_EQ(first[i].key, whole[i].key) << i;
}

TEST(Shapes, TheLargestCostIsBoundedByTheLimit) {  // --max-cost 24: the limit, not the space, bounds it
  const auto shapes = enumerate_shapes(parse_operations("all"), 24, 20'000);
  ASSERT_EQ(shapes.size(), 20'000u);
  for (const Shape& s : shapes) {
    EXPECT_LE(s.cost, 24);
    EXPECT_LE(s.constants, kMaxShapeConstants);
  }
}

TEST(Shapes, ConstantsAreSetInNodeOrder) {
  const auto shapes = enumerate_shapes(parse_operations("fma,max,mul"), 3, 1'000'000);
  const auto it = std::ranges::find_if(shapes, [](const Shape& s) { return s.key == "max(c * 7 + 7, 0) ^ 2"; });
  ASSERT_NE(it, shapes.end());
  const double values[] = {2.0, -1.0};
  EXPECT_EQ(expr::to_infix(with_constants(*it, values)), "max(c * 2 - 1, 0) ^ 2");
}

TEST(Operations, NamesParseAndUnknownOnesAreRefused) {
  EXPECT_EQ(parse_operations("fma,max").size(), 2u);
  EXPECT_EQ(parse_operations("all").size(), kOperationCount);
  EXPECT_THROW(parse_operations("fma,tan"), InvalidField);
  EXPECT_THROW(parse_operations(""), InvalidField);
}

}  // namespace
}  // namespace specula::design
