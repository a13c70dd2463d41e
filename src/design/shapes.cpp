// Exhaustive enumeration of lobe shapes by cost, bottom-up as fit's enumeration of forms: every
// shape of cost k is a step applied to shapes of cost k − (the step's cost), or a binary step
// joining two shapes whose costs add up. Steps that give back what a cheaper shape already is
// (an affine map of an affine map, a clamp of something ≥ 0, √(x²), (√x)²) are not taken.
#include "shapes.h"

#include <algorithm>
#include <array>
#include <unordered_set>

#include "specula/exceptions.h"

namespace specula::design {

using expr::Node;
using expr::Op;
using Step = Shape::Step;

namespace {

Node constant(double value) { return {Op::constant, 0, value}; }
Node exact(int value) { return expr::exact_constant(value, 1, expr::Symbol::one); }
Node op(Op o) { return {o, 0, 0}; }

// The shape printed in the search's variables, every free constant as the same number: the
// structure alone.
std::string key_of(const std::vector<Node>& nodes, const std::vector<std::string>& variables) {
  std::vector<Node> printed = nodes;
  for (auto& n : printed)
    if (n.op == Op::constant && !expr::is_exact(n)) n.value = 7;
  return expr::to_infix(expr::Expression(std::move(printed), variables));
}

Shape leaf(std::uint32_t variable) {
  Shape s;
  s.nodes = {{Op::variable, variable, 0}};
  s.nonnegative = true;
  return s;
}

Shape unary(const Shape& x, Step step, int cost) {
  Shape s;
  s.nodes = x.nodes;
  s.constants = x.constants;
  switch (step) {
    case Step::affine:
      s.nodes.insert(s.nodes.end(), {constant(1), op(Op::mul), constant(0), op(Op::add)});
      s.constants += 2;
      break;
    case Step::square: s.nodes.insert(s.nodes.end(), {exact(2), op(Op::pow)}); break;
    case Step::clamp: s.nodes.insert(s.nodes.end(), {exact(0), op(Op::max)}); break;
    case Step::sqrt: s.nodes.push_back(op(Op::sqrt)); break;
    case Step::exp: s.nodes.push_back(op(Op::exp)); break;
    case Step::log2: s.nodes.push_back(op(Op::log2)); break;
    case Step::leaf:
    case Step::product:
    case Step::sum:
    case Step::quotient:
    case Step::combination: throw std::logic_error("not a unary step");
  }
  s.step = step;
  s.cost = x.cost + cost;
  s.nonnegative = step == Step::square || step == Step::clamp || step == Step::sqrt || step == Step::exp;
  return s;
}

Shape binary(const Shape& x, const Shape& y, Step step, int cost) {
  const bool combination = step == Step::combination;
  Shape s;
  s.nodes = x.nodes;
  if (combination) s.nodes.insert(s.nodes.end(), {constant(1), op(Op::mul)});
  s.nodes.insert(s.nodes.end(), y.nodes.begin(), y.nodes.end());
  if (combination) s.nodes.insert(s.nodes.end(), {constant(1), op(Op::mul)});
  s.nodes.push_back(op(step == Step::product ? Op::mul : step == Step::quotient ? Op::div : Op::add));
  s.constants = x.constants + y.constants + (combination ? 2 : 0);
  s.step = step;
  s.cost = x.cost + y.cost + cost;
  s.nonnegative = !combination && x.nonnegative && y.nonnegative;
  return s;
}

// Whether `step` on x gives a shape no cheaper shape already is.
bool worth_applying(Step step, const Shape& x) {
  switch (step) {
    case Step::affine: return x.step != Step::affine;  // a(bx + c) + d is one affine map
    case Step::clamp: return !x.nonnegative;
    case Step::square: return x.step != Step::sqrt;
    case Step::sqrt: return x.step != Step::square;
    case Step::exp: return x.step != Step::log2;
    case Step::log2: return x.step != Step::exp;
    case Step::leaf:
    case Step::product:
    case Step::sum:
    case Step::quotient:
    case Step::combination: return true;
  }
  return true;
}

struct UnaryStep {
  Operation operation;
  Step step;
};
constexpr UnaryStep kUnary[] = {{Operation::fma, Step::affine}, {Operation::mul, Step::square},
                                {Operation::max, Step::clamp},  {Operation::sqrt, Step::sqrt},
                                {Operation::exp, Step::exp},    {Operation::log2, Step::log2}};
struct BinaryStep {
  Operation operation;
  Step step;
  bool commutative;
};
constexpr BinaryStep kBinary[] = {{Operation::mul, Step::product, true},
                                  {Operation::add, Step::sum, true},
                                  {Operation::div, Step::quotient, false},
                                  {Operation::fma, Step::combination, true}};

// The step's cost, or 0 where `operations` lacks what it needs (a combination: an fma and a mul).
int binary_cost(const BinaryStep& b, const std::function<bool(Operation)>& allowed) {
  if (!allowed(b.operation)) return 0;
  if (b.step != Step::combination) return operation_cost(b.operation);
  return allowed(Operation::mul) ? operation_cost(Operation::fma) + operation_cost(Operation::mul) : 0;
}

// Whether the binary step on x and y is taken: a combination a·x + b·y only of shapes without
// free constants (a linear model in computed features: with constants in x or y it would multiply
// the shapes without adding to what they compute, a·(px + q) + b·y being the affine map of a·x + b·y).
bool worth_joining(Step step, const Shape& x, const Shape& y) {
  return step != Step::combination || (x.constants == 0 && y.constants == 0);
}

}  // namespace

expr::Expression Shape::expression(const std::vector<std::string>& variables) const { return expr::Expression(nodes, variables); }

expr::Expression with_constants(const Shape& shape, std::span<const double> values, const std::vector<std::string>& variables) {
  std::vector<Node> nodes = shape.nodes;
  std::size_t k = 0;
  for (auto& n : nodes)
    if (n.op == Op::constant && !expr::is_exact(n)) {
      if (k >= values.size()) throw InvalidArgument("fewer constant values than the shape's constants");
      n.value = values[k++];
    }
  return expr::Expression(std::move(nodes), variables);
}

std::vector<Shape> enumerate_shapes(std::span<const Operation> operations, int max_cost, std::size_t limit,
                                    const std::function<bool()>& stop, const std::vector<std::string>& variables) {
  const auto allowed = [&](Operation o) { return std::ranges::find(operations, o) != operations.end(); };
  // at_most[cost][k]: the indices into `all` of the shapes of that cost with at most k free
  // constants, in the order found. A binary step pairs x only with the y whose constants fit, so
  // every pair visited builds a shape and the work is bounded by `limit`.
  using ByConstants = std::array<std::vector<std::size_t>, kMaxShapeConstants + 1>;
  std::vector<ByConstants> at_most(static_cast<std::size_t>(std::max(max_cost, 0)) + 1);
  std::vector<Shape> all;
  std::unordered_set<std::string> seen;
  bool stopped = false;
  const auto full = [&] {
    if (!stopped && stop && all.size() % 1024 == 1023) stopped = stop();
    return stopped || all.size() >= limit;
  };
  const auto add = [&](Shape s) {
    if (full() || s.constants > kMaxShapeConstants || s.cost > max_cost) return;
    s.key = key_of(s.nodes, variables);
    if (!seen.insert(s.key).second) return;
    for (int k = s.constants; k <= kMaxShapeConstants; ++k)
      at_most[static_cast<std::size_t>(s.cost)][static_cast<std::size_t>(k)].push_back(all.size());
    all.push_back(std::move(s));
  };
  const auto shapes = [&](int cost, int max_constants) -> const std::vector<std::size_t>& {
    return at_most[static_cast<std::size_t>(cost)][static_cast<std::size_t>(max_constants)];
  };
  for (std::uint32_t v = 0; v < variables.size(); ++v) add(leaf(v));
  for (int cost = 1; cost <= max_cost && !full(); ++cost) {
    for (const auto& u : kUnary) {
      const int step_cost = operation_cost(u.operation);
      if (!allowed(u.operation) || step_cost > cost) continue;
      for (const std::size_t x : shapes(cost - step_cost, kMaxShapeConstants))
        if (worth_applying(u.step, all[x])) add(unary(all[x], u.step, step_cost));
    }
    for (const auto& b : kBinary) {
      const int step_cost = binary_cost(b, allowed);
      if (step_cost == 0) continue;
      for (int left = 0; left <= cost - step_cost; ++left)
        for (const std::size_t x : shapes(left, kMaxShapeConstants))
          for (const std::size_t y : shapes(cost - step_cost - left, kMaxShapeConstants - all[x].constants)) {
            if (full()) return all;
            if (b.commutative && !(all[x].key < all[y].key)) continue;  // x·y once; x·x is the square
            if (b.step == Step::quotient && all[x].key == all[y].key) continue;
            if (!worth_joining(b.step, all[x], all[y])) continue;
            add(binary(all[x], all[y], b.step, step_cost));
          }
    }
  }
  return all;
}

}  // namespace specula::design
