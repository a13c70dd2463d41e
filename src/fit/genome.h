#pragma once
// Formulas under evolution: postfix node arrays (expr::Node) and the edits genetic programming
// makes to them. A subtree of a postfix array is a contiguous range ending at its root.
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "specula/expr/expr.h"
#include "specula/fit/fit.h"

namespace specula::fit {

using Genome = std::vector<expr::Node>;
using Rng = std::mt19937_64;

/// A constant the fit adjusts: any but an exact one (expr::is_exact: 1/3, 2, the exponent of a
/// merged power x·x = x^2), which every fit holds fixed.
inline bool is_free_constant(const expr::Node& n) { return n.op == expr::Op::constant && !expr::is_exact(n); }

/// The symbol of an operator ("+", "^", "neg") or a function's call name ("sqrt", "pow"); "" for
/// a leaf. --ops, --size-weights and canonical keys spell operators so.
std::string_view operator_symbol(expr::Op op);

/// start[i] is the first index of the subtree whose root is node i.
std::vector<std::size_t> subtree_starts(std::span<const expr::Node> nodes);

/// `nodes` with the subtree [first, last] replaced by `replacement`.
Genome replaced(std::span<const expr::Node> nodes, std::size_t first, std::size_t last,
                std::span<const expr::Node> replacement);

/// What a search may build formulas from.
struct Alphabet {
  std::vector<expr::Op> unary, binary;
  std::uint32_t variables = 1;
  Constants constants = Constants::fitted;
  SizeWeights weights;
  int max_size = 25;

  Alphabet(const Options& options, std::uint32_t variable_count);
  expr::Node random_leaf(Rng& rng) const;
  /// A random formula of at most `size` (weighted), grown from the root.
  Genome random_tree(Rng& rng, int size) const;
  /// Within the size limit, and with at most 64 constants (the derivative bit set).
  bool fits(std::span<const expr::Node> nodes) const;
};

/// Subtree crossover: a random subtree of `a` replaced by a random subtree of `b`.
Genome crossover(const Genome& a, const Genome& b, const Alphabet& alphabet, Rng& rng);

/// One random mutation: replace a subtree, change one node, wrap a subtree in an operator,
/// hoist a child over its parent, or perturb a constant.
Genome mutate(const Genome& g, const Alphabet& alphabet, Rng& rng);

/// `nodes` with every operator whose operands are all constants replaced by its value (where
/// finite): log(5.9) − exp(0.6) becomes one constant.
Genome folded_constants(std::span<const expr::Node> nodes);

/// A key equal for formulas that are the same up to the values of their free constants,
/// commutativity and associativity of + and ×, and x ÷ c = c′·x. An exact constant is keyed by
/// its value.
std::string canonical_key(std::span<const expr::Node> nodes);

}  // namespace specula::fit
