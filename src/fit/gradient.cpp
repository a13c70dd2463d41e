// Constant fitting's derivatives: a formula's values and its forward-mode derivatives by every
// constant, over chunks of rows; and which constants enter it linearly (constants.h).
#include <algorithm>
#include <bit>
#include <cmath>
#include <fmt/format.h>

#include "constants.h"

namespace specula::fit {

using expr::Node;
using expr::Op;

namespace {

constexpr std::size_t kChunk = 128;

struct Partials {
  double value, da, db;
};

// f(a, b) and its partial derivatives; unary ops ignore b.
template <Op op>
Partials apply(double a, double b) {
  if constexpr (op == Op::add) return {a + b, 1, 1};
  if constexpr (op == Op::sub) return {a - b, 1, -1};
  if constexpr (op == Op::mul) return {a * b, b, a};
  if constexpr (op == Op::div) return {a / b, 1 / b, -a / (b * b)};
  if constexpr (op == Op::pow) {
    const double v = std::pow(a, b);
    return {v, b * std::pow(a, b - 1), a > 0 ? v * std::log(a) : 0};
  }
  if constexpr (op == Op::min) return b < a ? Partials{b, 0, 1} : Partials{a, 1, 0};
  if constexpr (op == Op::max) return a < b ? Partials{b, 0, 1} : Partials{a, 1, 0};
  if constexpr (op == Op::neg) return {-a, -1, 0};
  if constexpr (op == Op::log) return {std::log(a), 1 / a, 0};
  if constexpr (op == Op::log2) return {std::log2(a), 1 / (a * std::numbers::ln2), 0};
  if constexpr (op == Op::exp) {
    const double v = std::exp(a);
    return {v, v, 0};
  }
  if constexpr (op == Op::sqrt) {
    const double v = std::sqrt(a);
    return {v, 0.5 / v, 0};
  }
  if constexpr (op == Op::abs) return {std::abs(a), a < 0 ? -1.0 : 1.0, 0};
  if constexpr (op == Op::sin) return {std::sin(a), std::cos(a), 0};
  if constexpr (op == Op::cos) return {std::cos(a), -std::sin(a), 0};
  if constexpr (op == Op::acos) return {std::acos(a), -1 / std::sqrt(1 - a * a), 0};
  if constexpr (op == Op::expm1) return {std::expm1(a), std::exp(a), 0};
  if constexpr (op == Op::log1p) return {std::log1p(a), 1 / (1 + a), 0};
  if constexpr (op == Op::asin) return {std::asin(a), 1 / std::sqrt(1 - a * a), 0};
  return {0, 0, 0};
}

// Values and partials of `op` over n rows: a ← f(a, b), da, db ← ∂f/∂a, ∂f/∂b.
template <Op op>
void apply_rows(std::size_t n, double* a, const double* b, double* da, double* db) {
  for (std::size_t i = 0; i < n; ++i) {
    const Partials p = apply<op>(a[i], b ? b[i] : 0.0);
    a[i] = p.value;
    da[i] = p.da;
    db[i] = p.db;
  }
}

void apply_rows(Op op, std::size_t n, double* a, const double* b, double* da, double* db) {
  switch (op) {
    case Op::add: return apply_rows<Op::add>(n, a, b, da, db);
    case Op::sub: return apply_rows<Op::sub>(n, a, b, da, db);
    case Op::mul: return apply_rows<Op::mul>(n, a, b, da, db);
    case Op::div: return apply_rows<Op::div>(n, a, b, da, db);
    case Op::pow: return apply_rows<Op::pow>(n, a, b, da, db);
    case Op::min: return apply_rows<Op::min>(n, a, b, da, db);
    case Op::max: return apply_rows<Op::max>(n, a, b, da, db);
    case Op::neg: return apply_rows<Op::neg>(n, a, b, da, db);
    case Op::log: return apply_rows<Op::log>(n, a, b, da, db);
    case Op::log2: return apply_rows<Op::log2>(n, a, b, da, db);
    case Op::exp: return apply_rows<Op::exp>(n, a, b, da, db);
    case Op::sqrt: return apply_rows<Op::sqrt>(n, a, b, da, db);
    case Op::abs: return apply_rows<Op::abs>(n, a, b, da, db);
    case Op::sin: return apply_rows<Op::sin>(n, a, b, da, db);
    case Op::cos: return apply_rows<Op::cos>(n, a, b, da, db);
    case Op::acos: return apply_rows<Op::acos>(n, a, b, da, db);
    case Op::expm1: return apply_rows<Op::expm1>(n, a, b, da, db);
    case Op::log1p: return apply_rows<Op::log1p>(n, a, b, da, db);
    case Op::asin: return apply_rows<Op::asin>(n, a, b, da, db);
    case Op::constant:
    case Op::variable: return;
  }
}

// The evaluation stack for one chunk: slot s holds a value block and a derivative block per
// constant, each kChunk long. Only the blocks of the constants in depends(s) (a bit set) are
// meaningful; the others are zero by definition.
class ChunkStack {
 public:
  void reset(std::size_t depth, std::size_t constants) {
    blocks_ = constants + 1;
    if (data_.size() < depth * blocks_ * kChunk) data_.resize(depth * blocks_ * kChunk);
    depends_.resize(depth);
  }
  double* value(std::size_t slot) { return &data_[slot * blocks_ * kChunk]; }
  double* gradient(std::size_t slot, std::size_t k) { return value(slot) + (k + 1) * kChunk; }
  std::uint64_t& depends(std::size_t slot) { return depends_[slot]; }

 private:
  std::size_t blocks_ = 1;
  std::vector<double> data_;
  std::vector<std::uint64_t> depends_;
};

std::size_t stack_depth(std::span<const Node> nodes) {
  std::size_t top = 0, depth = 0;
  for (const Node& n : nodes) {
    top = top + 1 - static_cast<std::size_t>(expr::arity(n.op));
    depth = std::max(depth, top);
  }
  return depth;
}

void push_leaf(ChunkStack& s, std::size_t slot, const Node& node, std::size_t constant_index,
               const Rows& rows, std::size_t first, std::size_t n) {
  double* v = s.value(slot);
  if (node.op == Op::variable) {
    std::copy_n(rows.columns[node.var].data() + first, n, v);
    s.depends(slot) = 0;
    return;
  }
  std::fill_n(v, n, node.value);
  if (expr::is_exact(node)) {  // held fixed: no derivative
    s.depends(slot) = 0;
    return;
  }
  std::fill_n(s.gradient(slot, constant_index), n, 1.0);
  s.depends(slot) = std::uint64_t{1} << constant_index;
}

// Applies `op` to slots a (and b = a + 1), leaving the result in slot a: the chain rule over
// the constants either operand depends on.
// x^b for an exponent that depends on no constant: no ∂/∂b (its log), and for b = 2 (the
// designer's squares, most of its powers) ∂/∂x = 2x without a second pow. The value stays
// std::pow's, bit for bit what expr's evaluator computes (glibc's pow(x, 2) is not always x·x).
void power_rows(std::size_t n, double* a, const double* b, double* da) {
  for (std::size_t i = 0; i < n; ++i) {
    da[i] = b[i] == 2 ? 2 * a[i] : b[i] * std::pow(a[i], b[i] - 1);
    a[i] = std::pow(a[i], b[i]);
  }
}

void apply_op(ChunkStack& s, Op op, std::size_t a, std::size_t n) {
  const bool binary = expr::arity(op) == 2;
  std::array<double, kChunk> da, db;
  const std::uint64_t in_a = s.depends(a), in_b = binary ? s.depends(a + 1) : 0;
  if (op == Op::pow && in_b == 0)
    power_rows(n, s.value(a), s.value(a + 1), da.data());
  else
    apply_rows(op, n, s.value(a), binary ? s.value(a + 1) : nullptr, da.data(), db.data());
  for (std::uint64_t left = in_a | in_b; left != 0; left &= left - 1) {
    const auto k = static_cast<std::size_t>(std::countr_zero(left));
    const std::uint64_t bit = std::uint64_t{1} << k;
    double* ka = s.gradient(a, k);
    const double* kb = binary ? s.gradient(a + 1, k) : nullptr;
    if (!(in_b & bit))
      for (std::size_t i = 0; i < n; ++i) ka[i] *= da[i];
    else if (in_a & bit)
      for (std::size_t i = 0; i < n; ++i) ka[i] = ka[i] * da[i] + kb[i] * db[i];
    else
      for (std::size_t i = 0; i < n; ++i) ka[i] = kb[i] * db[i];
  }
  s.depends(a) = in_a | in_b;
}

}  // namespace

void evaluate_with_gradient(std::span<const Node> nodes, const Rows& rows,
                            std::vector<double>& value, std::vector<double>& gradient) {
  const std::size_t count = rows.size();
  const auto constants = static_cast<std::size_t>(std::count_if(nodes.begin(), nodes.end(), is_free_constant));
  if (constants > kMaxConstants)
    throw InvalidArgument(fmt::format("a formula may have at most {} constants", kMaxConstants));
  value.resize(count);
  gradient.assign(constants * count, 0);
  thread_local ChunkStack s;
  s.reset(stack_depth(nodes), constants);
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t n = std::min(kChunk, count - first);
    std::size_t top = 0, constant_index = 0;
    for (const Node& node : nodes) {
      const int operands = expr::arity(node.op);
      if (operands == 0) {
        push_leaf(s, top++, node, is_free_constant(node) ? constant_index++ : constants, rows, first, n);
      } else {
        top -= static_cast<std::size_t>(operands);
        apply_op(s, node.op, top++, n);
      }
    }
    std::copy_n(s.value(0), n, value.data() + first);
    for (std::uint64_t left = s.depends(0); left != 0; left &= left - 1) {
      const auto k = static_cast<std::size_t>(std::countr_zero(left));
      std::copy_n(s.gradient(0, k), n, gradient.data() + k * count + first);
    }
  }
}

namespace {

// Whether the formula is affine in the constants marked in `chosen` (indexed by node).
bool affine_in(std::span<const Node> nodes, const std::vector<bool>& chosen) {
  std::vector<bool> depends;  // stack: does the operand involve a chosen constant?
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Op op = nodes[i].op;
    const int operands = expr::arity(op);
    if (operands == 0) {
      depends.push_back(chosen[i]);
      continue;
    }
    const bool b = operands == 2 && depends.back();
    if (operands == 2) depends.pop_back();
    const bool a = depends.back();
    const bool linear_op = op == Op::add || op == Op::sub || op == Op::neg ||
                           (op == Op::mul && !(a && b)) || (op == Op::div && !b);
    if ((a || b) && !linear_op) return false;
    depends.back() = a || b;
  }
  return true;
}

}  // namespace

std::vector<bool> linear_constants(std::span<const Node> nodes) {
  std::vector<bool> chosen(nodes.size(), false);
  std::vector<bool> linear;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!is_free_constant(nodes[i])) continue;
    chosen[i] = true;
    if (!affine_in(nodes, chosen)) chosen[i] = false;
    linear.push_back(chosen[i]);
  }
  return linear;
}

}  // namespace specula::fit
