#pragma once
// RapidCheck generator of random expressions over x and y: postfix trees of every op with
// variables and finite constants (negative ones, -0 and awkward magnitudes included).
#include <rapidcheck.h>

#include <cmath>
#include <ostream>
#include <vector>

#include "specula/expr/expr.h"

namespace specula::expr {

// RapidCheck shows a failing expression in infix.
inline void showValue(const Expression& e, std::ostream& os) { os << to_infix(e); }

namespace testing {

inline rc::Gen<double> random_constant() {
  return rc::gen::weightedOneOf<double>({
      {3, rc::gen::element(0.0, -0.0, 1.0, 2.0, -1.0, 0.5, 3.0, 0.1, 1e-5, 2.5e7)},
      {2, rc::gen::map(rc::gen::inRange(-100, 100), [](int n) { return n / 8.0; })},
      {2,
       rc::gen::suchThat(rc::gen::arbitrary<double>(), [](double v) { return std::isfinite(v); })},
  });
}

inline rc::Gen<std::vector<Node>> random_leaf() {
  return rc::gen::oneOf(rc::gen::map(random_constant(),
                                     [](double v) {
                                       return std::vector<Node>{{Op::constant, 0, v}};
                                     }),
                        rc::gen::map(rc::gen::inRange<std::uint32_t>(0, 2), [](std::uint32_t var) {
                          return std::vector<Node>{{Op::variable, var, 0}};
                        }));
}

inline rc::Gen<std::vector<Node>> random_tree(int depth);

inline rc::Gen<std::vector<Node>> random_unary(int depth) {
  return rc::gen::apply(
      [](Op op, std::vector<Node> operand) {
        operand.push_back({op, 0, 0});
        return operand;
      },
      rc::gen::element(Op::neg, Op::log, Op::log2, Op::exp, Op::sqrt, Op::abs, Op::sin, Op::cos,
                       Op::acos),
      random_tree(depth - 1));
}

inline rc::Gen<std::vector<Node>> random_binary(int depth) {
  return rc::gen::apply(
      [](Op op, std::vector<Node> left, const std::vector<Node>& right) {
        left.insert(left.end(), right.begin(), right.end());
        left.push_back({op, 0, 0});
        return left;
      },
      rc::gen::element(Op::add, Op::sub, Op::mul, Op::div, Op::pow, Op::min, Op::max),
      random_tree(depth - 1), random_tree(depth - 1));
}

inline rc::Gen<std::vector<Node>> random_tree(int depth) {
  if (depth == 0) return random_leaf();
  return rc::gen::weightedOneOf<std::vector<Node>>({
      {1, random_leaf()},
      {2, rc::gen::lazy([depth] { return random_unary(depth); })},
      {4, rc::gen::lazy([depth] { return random_binary(depth); })},
  });
}

inline rc::Gen<Expression> random_expression() {
  return rc::gen::map(random_tree(5), [](std::vector<Node> nodes) {
    return Expression(std::move(nodes), {"x", "y"});
  });
}

}  // namespace testing
}  // namespace specula::expr
