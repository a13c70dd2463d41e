// Postfix edits for genetic programming, and the canonical key that deduplicates formulas.
#include "genome.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fmt/format.h>
#include <string>

namespace specula::fit {

using expr::Node;
using expr::Op;

std::string_view operator_symbol(Op op) {
  switch (op) {
    case Op::constant:
    case Op::variable: return "";
    case Op::add: return "+";
    case Op::sub: return "-";
    case Op::mul: return "*";
    case Op::div: return "/";
    case Op::pow: return "^";
    case Op::neg: return "neg";
    case Op::min:
    case Op::max:
    case Op::log:
    case Op::log2:
    case Op::exp:
    case Op::sqrt:
    case Op::abs:
    case Op::sin:
    case Op::cos:
    case Op::acos:
    case Op::expm1:
    case Op::log1p:
    case Op::asin: return expr::function_name(op);
  }
  unreachable();
}

std::vector<std::size_t> subtree_starts(std::span<const Node> nodes) {
  std::vector<std::size_t> start(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int operands = expr::arity(nodes[i].op);
    if (operands == 0) start[i] = i;
    if (operands == 1) start[i] = start[i - 1];
    if (operands == 2) start[i] = start[start[i - 1] - 1];
  }
  return start;
}

Genome replaced(std::span<const Node> nodes, std::size_t first, std::size_t last,
                std::span<const Node> replacement) {
  Genome out(nodes.begin(), nodes.begin() + static_cast<std::ptrdiff_t>(first));
  out.insert(out.end(), replacement.begin(), replacement.end());
  out.insert(out.end(), nodes.begin() + static_cast<std::ptrdiff_t>(last) + 1, nodes.end());
  return out;
}

Alphabet::Alphabet(const Options& options, std::uint32_t variable_count)
    : variables(variable_count),
      constants(options.constants),
      weights(options.weights),
      max_size(options.max_size) {
  for (Op op : options.operators) (expr::arity(op) == 1 ? unary : binary).push_back(op);
}

namespace {

template <class T>
const T& pick(const std::vector<T>& items, Rng& rng) {
  return items[std::uniform_int_distribution<std::size_t>(0, items.size() - 1)(rng)];
}

std::size_t pick_index(std::size_t n, Rng& rng) {
  return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng);
}

bool chance(double p, Rng& rng) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; }

double random_constant(Constants constants, Rng& rng) {
  if (constants == Constants::integer)
    return static_cast<double>(std::uniform_int_distribution<int>(1, 3)(rng));
  return std::uniform_real_distribution<double>(0.5, 2.0)(rng);
}

void grow(const Alphabet& a, Rng& rng, int size, Genome& out) {
  const int unary_cost = a.unary.empty() ? 1 << 20 : 1 + a.weights.of(a.unary.front());
  const bool can_binary = !a.binary.empty() && size >= 3;
  const bool can_unary = !a.unary.empty() && size >= unary_cost;
  if (size <= 1 || (!can_binary && !can_unary) || chance(0.15, rng)) {
    out.push_back(a.random_leaf(rng));
    return;
  }
  if (can_unary && (!can_binary || chance(0.2, rng))) {
    const Op op = pick(a.unary, rng);
    grow(a, rng, size - a.weights.of(op), out);
    out.push_back({op, 0, 0});
    return;
  }
  const Op op = pick(a.binary, rng);
  const int children = std::max(2, size - a.weights.of(op));
  const int left = std::uniform_int_distribution<int>(1, children - 1)(rng);
  grow(a, rng, left, out);
  grow(a, rng, children - left, out);
  out.push_back({op, 0, 0});
}

// A uniformly chosen node of g, as the subtree [first, last] it roots.
std::pair<std::size_t, std::size_t> random_subtree(const Genome& g, Rng& rng) {
  const auto starts = subtree_starts(g);
  const std::size_t last = pick_index(g.size(), rng);
  return {starts[last], last};
}

Genome change_node(const Genome& g, const Alphabet& a, Rng& rng) {
  Genome out = g;
  Node& node = out[pick_index(out.size(), rng)];
  const int operands = expr::arity(node.op);
  if (operands == 0) node = a.random_leaf(rng);
  // A simplified formula may hold − or negation outside the alphabet (simplified.h): such a node
  // stays when the alphabet has no operator of its arity to put in its place.
  if (operands == 1 && !a.unary.empty()) node.op = pick(a.unary, rng);
  if (operands == 2 && !a.binary.empty()) node.op = pick(a.binary, rng);
  return out;
}

Genome wrap(const Genome& g, const Alphabet& a, Rng& rng) {
  const auto [first, last] = random_subtree(g, rng);
  Genome sub(g.begin() + static_cast<std::ptrdiff_t>(first),
             g.begin() + static_cast<std::ptrdiff_t>(last) + 1);
  if (!a.unary.empty() && (a.binary.empty() || chance(0.2, rng))) {
    sub.push_back({pick(a.unary, rng), 0, 0});
  } else {
    const Node leaf = a.random_leaf(rng);
    if (chance(0.5, rng))
      sub.push_back(leaf);
    else
      sub.insert(sub.begin(), leaf);
    sub.push_back({pick(a.binary, rng), 0, 0});
  }
  return replaced(g, first, last, sub);
}

Genome hoist(const Genome& g, Rng& rng) {
  const auto starts = subtree_starts(g);
  std::vector<std::size_t> operators;
  for (std::size_t i = 0; i < g.size(); ++i)
    if (expr::arity(g[i].op) > 0) operators.push_back(i);
  if (operators.empty()) return g;
  const std::size_t root = pick(operators, rng);
  std::size_t child = root - 1;  // the last operand
  if (expr::arity(g[root].op) == 2 && chance(0.5, rng)) child = starts[root - 1] - 1;
  const std::span<const Node> kept(g.data() + starts[child], child - starts[child] + 1);
  return replaced(g, starts[root], root, kept);
}

Genome perturb_constant(const Genome& g, const Alphabet& a, Rng& rng) {
  std::vector<std::size_t> constants;
  for (std::size_t i = 0; i < g.size(); ++i)
    if (g[i].op == Op::constant) constants.push_back(i);
  if (constants.empty()) return change_node(g, a, rng);
  Genome out = g;
  Node& node = out[pick(constants, rng)];
  double value = node.value;
  if (a.constants == Constants::integer)
    value += chance(0.5, rng) ? 1 : -1;
  else
    value = chance(0.2, rng) ? -value
                              : value * std::exp(std::normal_distribution<double>(0, 1)(rng));
  node = Node{Op::constant, 0, value};  // an exact constant perturbed is free from then on
  return out;
}

}  // namespace

Node Alphabet::random_leaf(Rng& rng) const {
  if (constants != Constants::none && chance(0.4, rng))
    return {Op::constant, 0, random_constant(constants, rng)};
  return {Op::variable, std::uniform_int_distribution<std::uint32_t>(0, variables - 1)(rng), 0};
}

bool Alphabet::fits(std::span<const Node> nodes) const {
  const auto constants =
      std::count_if(nodes.begin(), nodes.end(), [](const Node& n) { return n.op == Op::constant; });
  return weights.of(nodes) <= max_size && constants <= 64;
}

Genome Alphabet::random_tree(Rng& rng, int size) const {
  Genome out;
  grow(*this, rng, size, out);
  return out;
}

Genome crossover(const Genome& a, const Genome& b, const Alphabet& alphabet, Rng& rng) {
  for (int attempt = 0; attempt < 4; ++attempt) {
    const auto [first, last] = random_subtree(a, rng);
    const auto [from, to] = random_subtree(b, rng);
    Genome child = replaced(a, first, last, std::span<const Node>(b.data() + from, to - from + 1));
    if (alphabet.fits(child)) return child;
  }
  return a;
}

Genome mutate(const Genome& g, const Alphabet& alphabet, Rng& rng) {
  for (int attempt = 0; attempt < 4; ++attempt) {
    Genome child;
    switch (std::uniform_int_distribution<int>(0, 4)(rng)) {
      case 0: {
        const auto [first, last] = random_subtree(g, rng);
        child = replaced(g, first, last,
                         alphabet.random_tree(rng, std::uniform_int_distribution<int>(1, 7)(rng)));
        break;
      }
      case 1: child = change_node(g, alphabet, rng); break;
      case 2: child = wrap(g, alphabet, rng); break;
      case 3: child = hoist(g, rng); break;
      default: child = perturb_constant(g, alphabet, rng); break;
    }
    if (alphabet.fits(child)) return child;
  }
  return g;
}

Genome folded_constants(std::span<const Node> nodes) {
  Genome out;
  for (const Node& node : nodes) {
    const auto operands = static_cast<std::size_t>(expr::arity(node.op));
    const bool foldable = operands > 0 && std::all_of(out.end() - static_cast<std::ptrdiff_t>(operands), out.end(),
                                                      [](const Node& n) { return n.op == Op::constant; });
    if (foldable) {
      Genome alone(out.end() - static_cast<std::ptrdiff_t>(operands), out.end());
      alone.push_back(node);
      const double value = expr::evaluate(expr::Expression(std::move(alone), {}), {});
      if (std::isfinite(value)) {
        out.resize(out.size() - operands);
        out.push_back({Op::constant, 0, value});
        continue;
      }
    }
    out.push_back(node);
  }
  return out;
}

namespace {

// A canonical subtree: its key, and for + and × the keys of its flattened operands.
struct Canon {
  Op op = Op::constant;
  std::vector<std::string> terms;
  std::string key;
};

const Canon kConstant{Op::constant, {}, "c"};

bool is_free(const Canon& c) { return c.op == Op::constant && c.key == "c"; }

std::string op_symbol(Op op) { return std::string(operator_symbol(op)); }

// + or × of operands: nested same-op operands flattened, constants merged into one, sorted.
Canon associative(Op op, std::initializer_list<const Canon*> operands) {
  Canon out{op, {}, {}};
  bool constant = false;
  for (const Canon* c : operands) {
    if (c->op == op) {
      for (const auto& t : c->terms) {
        if (t == "c")
          constant = true;
        else
          out.terms.push_back(t);
      }
    } else if (is_free(*c)) {
      constant = true;
    } else {
      out.terms.push_back(c->key);
    }
  }
  std::sort(out.terms.begin(), out.terms.end());
  if (constant) out.terms.push_back("c");
  out.key = op_symbol(op) + "(";
  for (std::size_t i = 0; i < out.terms.size(); ++i) out.key += (i ? "," : "") + out.terms[i];
  out.key += ")";
  return out;
}

Canon combine(Op op, const Canon* a, const Canon* b) {
  const bool constant_a = a->op == Op::constant;
  const bool constant_b = b == nullptr || b->op == Op::constant;
  if (constant_a && constant_b) return kConstant;  // folded: free
  if (op == Op::add || op == Op::mul) return associative(op, {a, b});
  if (op == Op::div && b && is_free(*b)) return associative(Op::mul, {a, &kConstant});
  if (op == Op::sub && b && is_free(*b)) return associative(Op::add, {a, &kConstant});
  std::string key = op_symbol(op) + "(" + a->key + (b ? "," + b->key : "") + ")";
  return {op, {}, std::move(key)};
}

}  // namespace

std::string canonical_key(std::span<const Node> nodes) {
  std::vector<Canon> stack;
  for (const Node& node : nodes) {
    const int operands = expr::arity(node.op);
    if (operands == 0) {
      if (is_free_constant(node))
        stack.push_back(kConstant);
      else if (node.op == Op::constant)
        stack.push_back(Canon{Op::constant, {}, fmt::format("k{:x}", std::bit_cast<std::uint64_t>(node.value))});
      else
        stack.push_back(Canon{Op::variable, {}, fmt::format("x{}", node.var)});
      continue;
    }
    const Canon* a = &stack[stack.size() - static_cast<std::size_t>(operands)];
    const Canon* b = operands == 2 ? &stack.back() : nullptr;
    Canon c = combine(node.op, a, b);
    stack.resize(stack.size() - static_cast<std::size_t>(operands));
    stack.push_back(std::move(c));
  }
  return stack.back().key;
}

}  // namespace specula::fit
