// specula::expr::simplify (include/specula/expr/simplify.h). The postfix expression becomes a tree
// whose sums and products hold any number of operands; each is rewritten bottom-up into a
// canonical form (a sum: terms in key order, then its constant; a product: its coefficient, then
// factors base^exponent in key order), and the tree is written back as postfix.
#include "specula/expr/simplify.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fmt/format.h>
#include <iterator>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace specula::expr {
namespace {

struct Tree {
  Op op = Op::constant;
  double value = 0;        ///< Op::constant
  std::uint32_t var = 0;   ///< Op::variable
  std::vector<Tree> kids;  ///< add and mul: two or more; other ops: their arity
  Node leaf{};             ///< a leaf as it came: an exact constant keeps its form while unchanged
};

Tree constant(double value) { return {Op::constant, value, 0, {}, Node{Op::constant, 0, value}}; }

/// The node a leaf is written as: its own while its value is unchanged (an exact constant stays
/// exact), else a plain one.
Node leaf_node(const Tree& t) {
  if (t.leaf.op == t.op && std::bit_cast<std::uint64_t>(t.leaf.value) == std::bit_cast<std::uint64_t>(t.value)) return t.leaf;
  return Node{t.op, t.var, t.value};
}

/// −c for a constant, exact if c was.
Tree negated_constant(const Tree& c) {
  Tree out = constant(-c.value);
  if (is_exact(leaf_node(c))) {
    out.leaf = leaf_node(c);
    out.leaf.numerator = static_cast<std::int16_t>(-out.leaf.numerator);
    out.leaf.value = -out.leaf.value;
  }
  return out;
}
bool is_constant(const Tree& t) { return t.op == Op::constant; }
bool is_constant(const Tree& t, double value) { return is_constant(t) && t.value == value; }

Tree from_postfix(std::span<const Node> nodes) {
  std::vector<Tree> stack;
  for (const Node& node : nodes) {
    Tree t{node.op, node.value, node.var, {}, node};
    const auto operands = static_cast<std::size_t>(arity(node.op));
    t.kids.assign(std::make_move_iterator(stack.end() - static_cast<std::ptrdiff_t>(operands)),
                  std::make_move_iterator(stack.end()));
    stack.resize(stack.size() - operands);
    stack.push_back(std::move(t));
  }
  return std::move(stack.back());
}

/// A text that is equal for equal trees (constants by their bits): the canonical order's key.
void append_key(const Tree& t, std::string& key) {
  key += static_cast<char>('A' + static_cast<int>(t.op));
  if (t.op == Op::constant) fmt::format_to(std::back_inserter(key), "{:x}", std::bit_cast<std::uint64_t>(t.value));
  if (t.op == Op::variable) fmt::format_to(std::back_inserter(key), "{}", t.var);
  if (t.kids.empty()) return;
  key += '(';
  for (const Tree& kid : t.kids) {
    append_key(kid, key);
    key += ',';
  }
  key += ')';
}

std::string key_of(const Tree& t) {
  std::string key;
  append_key(t, key);
  return key;
}

void sort_by_key(std::vector<Tree>& trees) {
  std::vector<std::pair<std::string, Tree>> keyed;
  for (Tree& t : trees) keyed.emplace_back(key_of(t), std::move(t));
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  trees.clear();
  for (auto& [key, t] : keyed) trees.push_back(std::move(t));
}

void append_postfix(const Tree& t, std::vector<Node>& out) {
  for (const Tree& kid : t.kids) append_postfix(kid, out);
  out.push_back(t.kids.empty() ? leaf_node(t) : Node{t.op, t.var, t.value});
}

/// The value of an op over constant operands, as evaluate() computes it (nullopt if not finite).
std::optional<double> folded(const Tree& t) {
  std::vector<Node> nodes;
  append_postfix(t, nodes);
  const double value = evaluate(Expression(std::move(nodes), {}), {});
  if (!std::isfinite(value)) return std::nullopt;
  return value;
}

// ---------------------------------------------------------------------------------------------
// Exact arithmetic: constants that came exact (snapped, or structural: the −1 of a negation, the
// 2 of x + x) combine into exact ones while one symbol at most is involved and the parts fit a
// node (|p| ≤ 32767, q ≤ 255); a plain operand makes the result plain.

Tree exact_tree(const Node& n) {
  Tree t = constant(n.value);
  t.leaf = n;
  return t;
}

Tree exact_integer(int k) { return exact_tree(exact_constant(k, 1, Symbol::one)); }

std::optional<Node> exact_ratio(long long p, long long q, Symbol s) {
  if (q < 0) p = -p, q = -q;
  if (p == 0) return exact_constant(0, 1, Symbol::one);
  const long long common = std::gcd(p, q);
  p /= common, q /= common;
  if (q > 255 || std::abs(p) > 32767) return std::nullopt;
  return exact_constant(static_cast<int>(p), static_cast<int>(q), s);
}

std::optional<Node> exact_times(const Node& a, const Node& b) {
  if (a.symbol != Symbol::one && b.symbol != Symbol::one) return std::nullopt;
  return exact_ratio(static_cast<long long>(a.numerator) * b.numerator, static_cast<long long>(a.denominator) * b.denominator,
                     a.symbol != Symbol::one ? a.symbol : b.symbol);
}

std::optional<Node> exact_plus(const Node& a, const Node& b) {
  if (a.numerator == 0) return b;
  if (b.numerator == 0) return a;
  if (a.symbol != b.symbol) return std::nullopt;
  return exact_ratio(static_cast<long long>(a.numerator) * b.denominator + static_cast<long long>(b.numerator) * a.denominator,
                     static_cast<long long>(a.denominator) * b.denominator, a.symbol);
}

/// Constants multiplied (or added) as they come: the double, and its exact form while every
/// operand was exact.
class Combined {
 public:
  explicit Combined(int identity) : value_(identity), exact_(exact_constant(identity, 1, Symbol::one)) {}

  void times(const Tree& c) {
    value_ *= c.value;
    const Node leaf = leaf_node(c);
    exact_ = exact_ && is_exact(leaf) ? exact_times(*exact_, leaf) : std::nullopt;
  }
  void plus(const Tree& c) {
    value_ += c.value;
    const Node leaf = leaf_node(c);
    exact_ = exact_ && is_exact(leaf) ? exact_plus(*exact_, leaf) : std::nullopt;
  }
  double value() const { return value_; }
  /// As a constant tree: the exact form where there is one (its value as its text reads).
  Tree tree() const { return exact_ ? exact_tree(*exact_) : constant(value_); }

 private:
  double value_;
  std::optional<Node> exact_;
};

// ---------------------------------------------------------------------------------------------
// Canonical sums and products

Tree product(std::vector<Tree> factors);
Tree sum(std::vector<Tree> terms);
std::optional<Tree> over_common_denominator(const Tree& sum_of_terms);
bool reads_negative(const Tree& t);

/// An exponent as a constant node: exact (a fit holds it fixed) when every exponent it came from
/// was — x·x = x^2, 1/x = x^-1, √x = x^0.5, or exact ones written so — and it is a fraction p/q
/// with q ≤ 12; else a plain constant, as free as the fitted exponent it came from.
Tree exponent_constant(double value, bool exact) {
  Tree t = constant(value);
  if (!exact) return t;
  for (int q = 1; q <= 12; ++q) {
    const double p = value * q;
    if (p != std::round(p) || std::abs(p) > 1000) continue;
    t.leaf = exact_constant(static_cast<int>(p), q, Symbol::one);
    t.value = t.leaf.value;
    break;
  }
  return t;
}

bool is_exact_constant(const Tree& t) { return is_constant(t) && is_exact(leaf_node(t)); }

/// The exact constant e (a snapped base: e^x).
bool is_euler_number(const Tree& t) {
  if (!is_exact_constant(t)) return false;
  const Node n = leaf_node(t);
  return n.symbol == Symbol::e && n.numerator == 1 && n.denominator == 1;
}

/// The exact constant equal to `value` (p/q or p·s/q, q ≤ 12), if there is one.
std::optional<Node> exact_equal_to(double value) {
  for (std::size_t s = 0; s < kSymbolCount; ++s) {
    const auto symbol = static_cast<Symbol>(s);
    for (int q = 1; q <= 12; ++q) {
      const double p = std::round(value * q / symbol_value(symbol));
      if (std::abs(p) > 1000) continue;
      const Node candidate = exact_constant(static_cast<int>(p), q, symbol);
      if (candidate.value == value) return candidate;
    }
  }
  return std::nullopt;
}

/// Whether `t` is built of exact constants only (an exact constant, or an elementary one).
bool is_elementary_constant(const Tree& t) {
  if (t.kids.empty()) return is_exact_constant(t);
  return std::all_of(t.kids.begin(), t.kids.end(), is_elementary_constant);
}

/// The functions whose value at an exact constant is kept as written (pow and sqrt go through power()).
bool is_elementary_op(Op op) {
  switch (op) {
    case Op::exp: case Op::log: case Op::log2: case Op::expm1: case Op::log1p:
    case Op::sin: case Op::cos: case Op::acos: case Op::asin: return true;
    default: return false;
  }
}

/// An op over exact constants only (exp(−1/2), (2π)^(−1/2), log(3)) is an elementary constant
/// (docs/fit.md): kept as written, its value no plain double, unless it is an exact constant
/// itself (4^(1/2) = 2, log(1) = 0). Over other constants it folds to a plain one.
Tree folded_or_elementary(Tree t) {
  const bool elementary = std::all_of(t.kids.begin(), t.kids.end(), is_exact_constant);
  const auto value = folded(t);
  if (!elementary) return value ? constant(*value) : t;
  if (!value) return t;
  if (const auto exact = exact_equal_to(*value)) return exact_tree(*exact);
  return t;
}

/// The variables known positive in the simplify() call under way (its `positive` argument).
thread_local const std::vector<bool>* known_positive = nullptr;

/// Whether t > 0 wherever it is defined, from the known positive variables: exp(·), positive
/// constants, and sums, products and powers of positive parts.
bool positive(const Tree& t) {
  switch (t.op) {
    case Op::constant: return t.value > 0;
    case Op::variable: return known_positive != nullptr && t.var < known_positive->size() && (*known_positive)[t.var];
    case Op::exp: return true;
    case Op::add:
    case Op::mul: return std::all_of(t.kids.begin(), t.kids.end(), [](const Tree& k) { return positive(k); });
    case Op::pow: return positive(t.kids[0]);
    default: return false;
  }
}

Tree exponential(Tree argument);
std::optional<std::pair<Tree, Tree>> common_factor(const Tree& sum_of_terms);

/// base^exponent, with the exponent a constant (exact if `exact`, exponent_constant).
Tree power(Tree base, double exponent, bool exact) {
  if (exponent == 0) return constant(1);
  if (exponent == 1) return base;
  const auto whole = [](double v) { return v == std::round(v); };
  const auto even = [&](double v) { return whole(v) && std::fmod(v, 2) == 0; };
  // (e^a)^b = e^(a·b): e^a > 0, so for every real b.
  if (base.op == Op::exp) return exponential(product({std::move(base.kids[0]), exponent_constant(exponent, exact)}));
  // (x³ − x)^0.5 = x^0.5·(x² − 1)^0.5 for x > 0: a positive factor common to every term leaves a
  // fractional power, where it may meet its like outside ((x/y)^1.5 / √(x³/y³ − x/y) = x/√(x² − y²)).
  if (base.op == Op::add && !whole(exponent)) {
    if (auto split = common_factor(base))
      return product({power(std::move(split->first), exponent, exact), power(std::move(split->second), exponent, exact)});
  }
  // (c·x)^k = c^k·x^k for whole k, or where every factor is ≥ 0 (a positive constant, an even
  // power): (1.5874·x^4)^1.5 = 2.0000·x^6.
  const auto nonnegative = [&](const Tree& f) {
    return (is_constant(f) && f.value >= 0) || (f.op == Op::pow && is_constant(f.kids[1]) && even(f.kids[1].value)) ||
           positive(f);
  };
  if (base.op == Op::mul && (whole(exponent) || std::all_of(base.kids.begin(), base.kids.end(), nonnegative))) {
    std::vector<Tree> factors;
    for (Tree& factor : base.kids) factors.push_back(power(std::move(factor), exponent, exact));
    return product(std::move(factors));
  }
  // (x^a)^b = x^(a·b) where both sides are defined alike: not for whole a and fractional b, where
  // x < 0 is in the left's domain and out of the right's — unless a and a·b are even, where both
  // are |x|^(a·b): (x^4)^1.5 = x^6, but (x^2)^0.5 = |x|.
  if (base.op == Op::pow && is_constant(base.kids[1])) {
    const double inner = base.kids[1].value;
    if (whole(exponent) || !whole(inner) || (even(inner) && even(inner * exponent)) || positive(base.kids[0])) {
      const bool inner_exact = is_exact_constant(base.kids[1]);
      return power(std::move(base.kids[0]), inner * exponent, exact && inner_exact);
    }
  }
  Tree t{Op::pow, 0, 0, {std::move(base), exponent_constant(exponent, exact)}};
  if (is_constant(t.kids[0])) return folded_or_elementary(std::move(t));
  return t;
}

/// −t. A negated sum is spread over its terms (product, below): −(a + b) = −a − b costs no node
/// and puts the terms where like terms meet them; another coefficient stays outside its sum
/// (2·(x + y) is smaller than 2·x + 2·y).
Tree negated(Tree t) { return product({exact_integer(-1), std::move(t)}); }

/// −(a + b) as −a − b, a canonical sum's terms negated one by one.
Tree negated_terms(Tree sum_of_terms) {
  std::vector<Tree> terms;
  for (Tree& term : sum_of_terms.kids) terms.push_back(negated(std::move(term)));
  return sum(std::move(terms));
}

struct Power {
  std::string key;
  Tree base;
  double exponent;
  bool exact;
};

/// A factor as base^exponent (exponent 1, exact, for a factor that is no power).
Power as_power(Tree factor) {
  if (factor.op == Op::pow && is_constant(factor.kids[1])) {
    const bool exact = is_exact_constant(factor.kids[1]);
    return {{}, std::move(factor.kids[0]), factor.kids[1].value, exact};
  }
  return {{}, std::move(factor), 1.0, true};
}

/// e^a·e^b = e^(a + b): the exponentials among `factors` become one.
void merge_exponentials(std::vector<Tree>& factors) {
  const auto is_exp = [](const Tree& f) { return f.op == Op::exp; };
  if (std::count_if(factors.begin(), factors.end(), is_exp) < 2) return;
  std::vector<Tree> arguments, others;
  for (Tree& f : factors) (is_exp(f) ? arguments.push_back(std::move(f.kids[0])) : others.push_back(std::move(f)));
  others.push_back(exponential(sum(std::move(arguments))));
  factors = std::move(others);
}

void write(const Tree& t, std::vector<Node>& out);

std::size_t written_size(const Tree& t) {
  std::vector<Node> out;
  write(t, out);
  return out.size();
}

bool same_tree(const Tree& a, const Tree& b) {
  if (a.op != b.op || a.var != b.var || a.kids.size() != b.kids.size()) return false;
  if (a.op == Op::constant && std::bit_cast<std::uint64_t>(a.value) != std::bit_cast<std::uint64_t>(b.value))
    return false;
  for (std::size_t k = 0; k < a.kids.size(); ++k)
    if (!same_tree(a.kids[k], b.kids[k])) return false;
  return true;
}

/// The base of a factor as product() merges it: b for b^c (c a constant), else the factor.
const Tree& base_of(const Tree& factor) {
  return factor.op == Op::pow && is_constant(factor.kids[1]) ? factor.kids[0] : factor;
}

/// Whether a term of the product's sum (its factor `sum_of_terms`) has a factor that merges with
/// one of the product's other factors (two constants, two exponentials, the same base): without
/// one, multiplying out shrinks nothing.
bool merges_with_a_term(const Tree& product_of_factors, const Tree& sum_of_terms) {
  const auto merges = [&](const Tree& factor) {
    return std::ranges::any_of(product_of_factors.kids, [&](const Tree& other) {
      return &other != &sum_of_terms &&
             ((factor.op == other.op && (factor.op == Op::constant || factor.op == Op::exp)) ||
              same_tree(base_of(factor), base_of(other)));
    });
  };
  return std::ranges::any_of(sum_of_terms.kids, [&](const Tree& term) {
    return term.op == Op::mul ? std::ranges::any_of(term.kids, merges) : merges(term);
  });
}

/// The product `t` of one sum and other factors, multiplied out where that is strictly smaller:
/// (x² − x)·x² = x⁴ − x³ (7 nodes, not 9), while 2·(x + y) and x·(x + 1) stay.
std::optional<Tree> distributed(const Tree& t) {
  const auto is_sum = [](const Tree& f) { return f.op == Op::add; };
  if (std::count_if(t.kids.begin(), t.kids.end(), is_sum) != 1) return std::nullopt;
  const auto sum_at = std::find_if(t.kids.begin(), t.kids.end(), is_sum);
  if (!merges_with_a_term(t, *sum_at)) return std::nullopt;
  std::vector<Tree> terms;
  for (const Tree& term : sum_at->kids) {
    std::vector<Tree> factors{term};
    for (auto f = t.kids.begin(); f != t.kids.end(); ++f)
      if (f != sum_at) factors.push_back(*f);
    terms.push_back(product(std::move(factors)));
  }
  Tree spread = sum(std::move(terms));
  if (written_size(spread) < written_size(t)) return spread;
  return std::nullopt;
}

Tree product(std::vector<Tree> factors) {
  std::vector<Tree> flat;
  for (Tree& f : factors) {
    if (f.op == Op::mul) std::move(f.kids.begin(), f.kids.end(), std::back_inserter(flat));
    else flat.push_back(std::move(f));
  }
  Combined coefficient(1);
  std::vector<Power> powers;
  for (Tree& f : flat) {
    if (is_constant(f)) {
      coefficient.times(f);
      continue;
    }
    Power factor = as_power(std::move(f));
    factor.key = key_of(factor.base);
    const auto same = std::find_if(powers.begin(), powers.end(), [&](const Power& p) { return p.key == factor.key; });
    if (same != powers.end()) {
      same->exponent += factor.exponent;
      same->exact = same->exact && factor.exact;
    } else {
      powers.push_back(std::move(factor));
    }
  }
  if (coefficient.value() == 0 || !std::isfinite(coefficient.value())) return coefficient.tree();
  std::vector<Tree> kept;
  for (Power& p : powers) {
    // (−a − b)^k = (−1)^k·(a + b)^k for whole k: the minus joins the coefficient, where a sum
    // above writes it as a subtraction.
    if (p.base.op == Op::add && reads_negative(p.base) && p.exponent == std::round(p.exponent)) {
      p.base = negated_terms(std::move(p.base));
      if (std::fmod(p.exponent, 2) != 0) coefficient.times(exact_integer(-1));
    }
    Tree factor = power(std::move(p.base), p.exponent, p.exact);
    if (is_constant(factor)) coefficient.times(factor);
    else kept.push_back(std::move(factor));
  }
  merge_exponentials(kept);
  for (auto it = kept.begin(); it != kept.end();) {  // e^(x − x + 1) = e, a coefficient
    if (!is_constant(*it)) { ++it; continue; }
    coefficient.times(*it);
    it = kept.erase(it);
  }
  if (kept.empty()) return coefficient.tree();
  if (coefficient.value() == -1 && kept.size() == 1 && kept.front().op == Op::add)  // −(a − b) = b − a
    return negated_terms(std::move(kept.front()));
  sort_by_key(kept);
  if (coefficient.value() != 1) kept.insert(kept.begin(), coefficient.tree());
  if (kept.size() == 1) return std::move(kept.front());
  Tree t{Op::mul, 0, 0, std::move(kept)};
  if (auto spread = distributed(t)) return std::move(*spread);
  return t;
}

/// A term as coefficient · rest (an exact 1 for a term without one).
std::pair<Tree, Tree> coefficient_and_rest(Tree term) {
  if (term.op != Op::mul || !is_constant(term.kids.front())) return {exact_integer(1), std::move(term)};
  Tree coefficient = std::move(term.kids.front());
  term.kids.erase(term.kids.begin());
  if (term.kids.size() == 1) return {std::move(coefficient), std::move(term.kids.front())};
  return {std::move(coefficient), std::move(term)};
}

/// Like terms: their rest and the sum of their coefficients.
struct Like {
  std::string key;
  Tree rest;
  Combined coefficient;
};

Tree sum(std::vector<Tree> terms) {
  std::vector<Tree> flat;
  for (Tree& t : terms) {
    if (t.op == Op::add) std::move(t.kids.begin(), t.kids.end(), std::back_inserter(flat));
    else flat.push_back(std::move(t));
  }
  Combined constant_part(0);
  std::vector<Like> likes;
  for (Tree& t : flat) {
    if (is_constant(t)) {
      constant_part.plus(t);
      continue;
    }
    auto [coefficient, rest] = coefficient_and_rest(std::move(t));
    std::string key = key_of(rest);
    auto same = std::find_if(likes.begin(), likes.end(), [&](const Like& l) { return l.key == key; });
    if (same == likes.end()) {
      likes.push_back({std::move(key), std::move(rest), Combined(0)});
      same = likes.end() - 1;
    }
    same->coefficient.plus(coefficient);
  }
  std::vector<Tree> kept;
  for (Like& l : likes) {
    if (l.coefficient.value() == 0) continue;
    kept.push_back(product({l.coefficient.tree(), std::move(l.rest)}));
  }
  sort_by_key(kept);
  if (constant_part.value() != 0 || kept.empty()) kept.push_back(constant_part.tree());
  if (kept.size() == 1) return std::move(kept.front());
  Tree t{Op::add, 0, 0, std::move(kept)};
  if (auto together = over_common_denominator(t)) return std::move(*together);
  return t;
}

bool is_reciprocal_sum(const Tree& f) { return f.op == Op::pow && is_constant(f.kids[1], -1) && f.kids[0].op == Op::add; }

/// The first sum D that a term of `sum_of_terms` divides by (a factor D^−1), if any.
const Tree* divisor_sum(const Tree& sum_of_terms) {
  for (const Tree& term : sum_of_terms.kids) {
    if (is_reciprocal_sum(term)) return &term.kids[0];
    if (term.op != Op::mul) continue;
    const auto factor = std::find_if(term.kids.begin(), term.kids.end(), is_reciprocal_sum);
    if (factor != term.kids.end()) return &factor->kids[0];
  }
  return nullptr;
}

/// Whether `term` has the factor divisor^−1.
bool divides_by(const Tree& term, const Tree& divisor) {
  const auto is_it = [&](const Tree& f) { return is_reciprocal_sum(f) && same_tree(f.kids[0], divisor); };
  return is_it(term) || (term.op == Op::mul && std::ranges::any_of(term.kids, is_it));
}

/// Whether t holds a constant that is not exact (a fitted one).
bool has_plain_constant(const Tree& t) {
  if (is_constant(t)) return !is_exact_constant(t);
  return std::ranges::any_of(t.kids, has_plain_constant);
}

/// Set while over_common_denominator builds its candidate: the product it makes may multiply the
/// fraction out again (distributed), which must not try the common denominator anew.
thread_local bool building_common_denominator = false;

/// a/D + b as (a + b·D)/D where that is strictly smaller: the numerator's like terms may cancel,
/// x/(x/2 − 5) − 2 = 10/(x/2 − 5). Defined where the sum is (D ≠ 0 there). Only over exact
/// constants (snapped or structural): fitted ones cancel only by an accident of rounding, and
/// trying every sum of a search costs it 8 % of its generations.
std::optional<Tree> over_common_denominator(const Tree& sum_of_terms) {
  if (building_common_denominator || has_plain_constant(sum_of_terms)) return std::nullopt;
  const Tree* divisor = divisor_sum(sum_of_terms);
  if (divisor == nullptr) return std::nullopt;
  struct Building {
    Building() { building_common_denominator = true; }
    ~Building() { building_common_denominator = false; }
  } building;
  std::vector<Tree> numerator;
  // b·D multiplied out term by term, so that its terms meet a's like ones: 3x − 3·(x − 10) = 30.
  for (const Tree& term : sum_of_terms.kids) {
    if (divides_by(term, *divisor)) numerator.push_back(product({term, *divisor}));
    else
      for (const Tree& part : divisor->kids) numerator.push_back(product({term, part}));
  }
  Tree together = product({sum(std::move(numerator)), power(*divisor, -1, true)});
  if (written_size(together) < written_size(sum_of_terms)) return together;
  return std::nullopt;
}

/// e^argument: e^(ln x) = x and e^(c·ln x) = x^c for x > 0.
Tree exponential(Tree argument) {
  if (argument.op == Op::log && positive(argument.kids[0])) return std::move(argument.kids[0]);
  if (argument.op == Op::mul && argument.kids.size() == 2 && is_constant(argument.kids[0]) &&
      argument.kids[1].op == Op::log && positive(argument.kids[1].kids[0])) {
    const bool exact = is_exact_constant(argument.kids[0]);
    return power(std::move(argument.kids[1].kids[0]), argument.kids[0].value, exact);
  }
  Tree t{Op::exp, 0, 0, {std::move(argument)}};
  if (is_constant(t.kids[0])) return folded_or_elementary(std::move(t));
  return t;
}

/// ln(argument): ln(e^a) = a; for positive parts ln(x^a) = a·ln x, and the log of a product with
/// an exponential or a power in it is the sum of the factors' logs (ln(2·e^x) = x + ln 2).
Tree logarithm(Tree argument) {
  if (argument.op == Op::exp) return std::move(argument.kids[0]);
  if (argument.op == Op::pow && positive(argument.kids[0]))
    return product({std::move(argument.kids[1]), logarithm(std::move(argument.kids[0]))});
  const auto splits = [](const Tree& f) { return f.op == Op::exp || f.op == Op::pow; };
  if (argument.op == Op::mul && positive(argument) && std::any_of(argument.kids.begin(), argument.kids.end(), splits)) {
    std::vector<Tree> logs;
    for (Tree& factor : argument.kids) logs.push_back(logarithm(std::move(factor)));
    return sum(std::move(logs));
  }
  Tree t{Op::log, 0, 0, {std::move(argument)}};
  if (is_constant(t.kids[0])) return folded_or_elementary(std::move(t));
  return t;
}

/// The factors of a term but its coefficient, each as base^exponent with its key.
std::vector<Power> factors_of(const Tree& term) {
  Tree rest = coefficient_and_rest(term).second;
  std::vector<Tree> parts;
  if (rest.op == Op::mul) parts = std::move(rest.kids);
  else parts.push_back(std::move(rest));
  std::vector<Power> out;
  for (Tree& part : parts) {
    if (is_constant(part)) continue;
    out.push_back(as_power(std::move(part)));
    out.back().key = key_of(out.back().base);
  }
  return out;
}

/// A sum as (its common factor, the sum divided by it): every positive base that each term has,
/// to the smallest of its exponents (exact where they all are). Nothing where there is none.
std::optional<std::pair<Tree, Tree>> common_factor(const Tree& sum_of_terms) {
  std::vector<std::vector<Power>> terms;
  for (const Tree& term : sum_of_terms.kids) terms.push_back(factors_of(term));
  std::vector<Tree> common;
  for (const Power& first : terms.front()) {
    if (!positive(first.base)) continue;
    double smallest = first.exponent;
    bool in_every_term = true, exact = first.exact;
    for (std::size_t k = 1; k < terms.size() && in_every_term; ++k) {
      const auto same = std::find_if(terms[k].begin(), terms[k].end(), [&](const Power& p) { return p.key == first.key; });
      in_every_term = same != terms[k].end();
      if (in_every_term) smallest = std::min(smallest, same->exponent), exact = exact && same->exact;
    }
    if (in_every_term && smallest != 0) common.push_back(power(first.base, smallest, exact));
  }
  if (common.empty()) return std::nullopt;
  Tree factor = product(std::move(common));
  std::vector<Tree> divided;
  for (const Tree& term : sum_of_terms.kids) divided.push_back(product({term, power(factor, -1, true)}));
  return std::make_pair(std::move(factor), sum(std::move(divided)));
}

/// Whether t is written with a leading minus: a product with a negative coefficient, or a sum
/// whose every term is so.
bool reads_negative(const Tree& t) {
  if (t.op == Op::mul) return is_constant(t.kids.front()) && t.kids.front().value < 0;
  if (t.op == Op::add)
    return std::all_of(t.kids.begin(), t.kids.end(),
                       [](const Tree& k) { return (is_constant(k) && k.value < 0) || reads_negative(k); });
  return false;
}

/// cos(−u) = cos(u), |−u| = |u|, sin(−u) = −sin(u): the minus leaves an even or odd function.
Tree with_symmetry(Tree t) {
  if (!reads_negative(t.kids[0])) return t;
  t.kids[0] = negated(std::move(t.kids[0]));
  return t.op == Op::sin ? negated(std::move(t)) : t;
}

Tree canonical(Tree t) {
  for (Tree& kid : t.kids) kid = canonical(std::move(kid));
  const bool all_constant = !t.kids.empty() && std::all_of(t.kids.begin(), t.kids.end(), [](const Tree& k) { return is_constant(k); });
  if (all_constant && t.op != Op::add && t.op != Op::mul && t.op != Op::pow && t.op != Op::sqrt) {
    if (is_elementary_op(t.op)) return folded_or_elementary(std::move(t));
    if (const auto value = folded(t)) return constant(*value);
  }
  switch (t.op) {
    case Op::constant:
    case Op::variable: return t;
    case Op::add: return sum(std::move(t.kids));
    case Op::sub: return sum({std::move(t.kids[0]), negated(std::move(t.kids[1]))});
    case Op::mul: return product(std::move(t.kids));
    case Op::div: return product({std::move(t.kids[0]), power(std::move(t.kids[1]), -1, true)});
    case Op::neg: return negated(std::move(t.kids[0]));
    case Op::sqrt: return power(std::move(t.kids[0]), 0.5, true);
    case Op::pow:
      if (is_constant(t.kids[1])) return power(std::move(t.kids[0]), t.kids[1].value, is_exact_constant(t.kids[1]));
      if (is_constant(t.kids[0], 1)) return std::move(t.kids[0]);  // 1^u = 1
      if (is_euler_number(t.kids[0])) return exponential(std::move(t.kids[1]));  // e^u: exp(u)
      // (e^a)^u = e^(a·u), but a constant's power stays one unless the merged form is smaller:
      // exp(-0.5) ^ x ^ 2 is a node smaller than exp(-0.5 * x ^ 2), exp(2) ^ (x / 2) two larger than exp(x).
      if (t.kids[0].op == Op::exp && !is_elementary_constant(t.kids[0]))
        return exponential(product({std::move(t.kids[0].kids[0]), std::move(t.kids[1])}));
      if (t.kids[0].op == Op::exp) {
        Tree merged = exponential(product({t.kids[0].kids[0], t.kids[1]}));
        if (written_size(merged) < written_size(t)) return merged;
      }
      return t;
    case Op::abs:
      if (positive(t.kids[0])) return std::move(t.kids[0]);
      return with_symmetry(std::move(t));
    case Op::sin:
    case Op::cos: return with_symmetry(std::move(t));
    case Op::log: return logarithm(std::move(t.kids[0]));
    case Op::exp: return exponential(std::move(t.kids[0]));
    case Op::min:
    case Op::max:
    case Op::log2:
    case Op::acos:
    case Op::expm1:
    case Op::log1p:
    case Op::asin: return t;
  }
  unreachable();
}

// ---------------------------------------------------------------------------------------------
// Back to postfix: subtraction for negative terms, division for negative powers

void write(const Tree& t, std::vector<Node>& out);

/// The magnitude of a term whose sign is negative (a constant below 0, or a product whose
/// coefficient is), and whether it was negative.
std::pair<Tree, bool> magnitude(Tree term) {
  if (is_constant(term) && term.value < 0) return {negated_constant(term), true};
  if (term.op == Op::mul && is_constant(term.kids.front()) && term.kids.front().value < 0) {
    term.kids.front() = negated_constant(term.kids.front());
    if (is_constant(term.kids.front(), 1)) term.kids.erase(term.kids.begin());
    if (term.kids.size() == 1) return {std::move(term.kids.front()), true};
    return {std::move(term), true};
  }
  return {std::move(term), false};
}

void write_sum(const Tree& t, std::vector<Node>& out) {
  std::vector<std::pair<Tree, bool>> terms;
  for (const Tree& kid : t.kids) terms.push_back(magnitude(kid));
  // Lead with a positive term where there is one: x − 1, not −1 + x.
  // With none, lead with the negative constant where there is one: −1 − x, not −x − 1.
  const auto first = std::find_if(terms.begin(), terms.end(), [](const auto& term) { return !term.second; });
  if (first != terms.end()) std::rotate(terms.begin(), first, first + 1);
  const auto constant_term = std::find_if(t.kids.begin(), t.kids.end(), [](const Tree& k) { return is_constant(k); });
  const bool constant_leads = first == terms.end() && constant_term != t.kids.end();
  if (constant_leads) {
    const auto at = static_cast<std::size_t>(constant_term - t.kids.begin());
    terms.erase(terms.begin() + static_cast<std::ptrdiff_t>(at));
    out.push_back(leaf_node(*constant_term));
  }
  for (std::size_t i = 0; i < terms.size(); ++i) {
    write(terms[i].first, out);
    if (i == 0 && !constant_leads) {
      if (terms[i].second) out.push_back({Op::neg, 0, 0});
      continue;
    }
    out.push_back({terms[i].second ? Op::sub : Op::add, 0, 0});
  }
}

/// base^exponent for a constant exponent > 0: base, sqrt(base) or pow(base, exponent).
void write_power(const Tree& base, const Tree& exponent, std::vector<Node>& out) {
  write(base, out);
  if (exponent.value == 1) return;
  if (exponent.value == 0.5) {
    out.push_back({Op::sqrt, 0, 0});
    return;
  }
  out.push_back(leaf_node(exponent));
  out.push_back({Op::pow, 0, 0});
}

void write_product(const Tree& t, std::vector<Node>& out) {
  std::vector<std::pair<const Tree*, Tree>> numerator, denominator;  // base, |exponent|
  double coefficient = 1;
  Node coefficient_node{};
  for (const Tree& kid : t.kids) {
    if (is_constant(kid)) {
      coefficient = kid.value;
      coefficient_node = leaf_node(kid);
      continue;
    }
    const bool is_power = kid.op == Op::pow && is_constant(kid.kids[1]);
    const Tree* base = is_power ? &kid.kids[0] : &kid;
    const Tree exponent = is_power ? kid.kids[1] : constant(1);
    if (exponent.value < 0) denominator.emplace_back(base, negated_constant(exponent));
    else numerator.emplace_back(base, exponent);
  }
  // −1 · x is written −x; another coefficient keeps its sign (−2·x, one node less than −(2·x)).
  const bool negated_once = coefficient == -1;
  if (negated_once) coefficient = 1;
  std::size_t written = 0;
  if (coefficient != 1 || numerator.empty()) {
    // The 1 of 1/√(2π) is exact, as the constant it divides: a fit must not move it.
    const bool elementary = coefficient == 1 && std::all_of(t.kids.begin(), t.kids.end(), is_elementary_constant);
    out.push_back(coefficient == coefficient_node.value && coefficient_node.op == Op::constant ? coefficient_node
                  : elementary ? exact_constant(1, 1, Symbol::one)
                               : Node{Op::constant, 0, coefficient});
    ++written;
  }
  for (const auto& [base, exponent] : numerator) {
    write_power(*base, exponent, out);
    if (++written > 1) out.push_back({Op::mul, 0, 0});
  }
  for (const auto& [base, exponent] : denominator) {
    write_power(*base, exponent, out);
    out.push_back({Op::div, 0, 0});
  }
  if (negated_once) out.push_back({Op::neg, 0, 0});
}

void write(const Tree& t, std::vector<Node>& out) {
  if (t.op == Op::add) return write_sum(t, out);
  if (t.op == Op::mul) return write_product(t, out);
  if (t.op == Op::pow && is_constant(t.kids[1])) return write_product({Op::mul, 0, 0, {t}}, out);
  for (const Tree& kid : t.kids) write(kid, out);
  out.push_back(t.kids.empty() ? leaf_node(t) : Node{t.op, t.var, t.value});
}

/// How many times the canonical form is rebuilt from its own postfix: a rewrite can expose
/// another (a factor that cancels once its sum has collected), and two passes nearly always
/// reach the fixed point; more would be a waste, never a loop.
constexpr int kPasses = 3;

Expression simplified(const Expression& e) {
  std::vector<Node> nodes(e.nodes().begin(), e.nodes().end());
  for (int pass = 0; pass < kPasses; ++pass) {
    std::vector<Node> next;
    write(canonical(from_postfix(nodes)), next);
    if (same_nodes(next, nodes)) break;
    nodes = std::move(next);
  }
  return Expression(std::move(nodes), e.variables());
}

}  // namespace

Expression simplify(const Expression& e, const std::vector<bool>& positive) {
  struct Facts {  // the sign facts hold for this call only
    explicit Facts(const std::vector<bool>& p) { known_positive = &p; }
    ~Facts() { known_positive = nullptr; }
  } facts(positive);
  try {
    return simplified(e);
  } catch (const InvalidArgument&) {  // a folded constant overflowed: the formula is kept as it is
    return e;
  }
}

bool same_nodes(std::span<const Node> a, std::span<const Node> b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const Node& x, const Node& y) {
    return x.op == y.op && x.var == y.var && std::bit_cast<std::uint64_t>(x.value) == std::bit_cast<std::uint64_t>(y.value);
  });
}

bool values_agree(std::span<const double> a, std::span<const double> b, double tolerance) {
  for (std::size_t r = 0; r < a.size(); ++r) {
    if (!std::isfinite(a[r]) || !std::isfinite(b[r])) {
      if (!(a[r] == b[r]) && !(std::isnan(a[r]) && std::isnan(b[r]))) return false;
      continue;
    }
    if (std::abs(a[r] - b[r]) > tolerance * std::max(std::abs(a[r]), std::abs(b[r]))) return false;
  }
  return true;
}

bool agrees_on(const Expression& a, const Expression& b, std::span<const std::span<const double>> columns,
               double tolerance) {
  const std::size_t rows = columns.empty() ? 0 : columns.front().size();
  std::vector<double> va(rows), vb(rows);
  evaluate_batch(a, columns, va);
  evaluate_batch(b, columns, vb);
  return values_agree(va, vb, tolerance);
}

}  // namespace specula::expr
