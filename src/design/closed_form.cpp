// Closed-form normalization of designed lobes (closed_form.h). The lobe's postfix nodes are read
// as a tree: its degree in c, with each clamp max(X, 0) of an X affine in c read as X; the lobe
// on either side of the clamp's kink (X, or 0, in its place); and the albedo integral as the sum,
// over each side's interval, of Gauss–Legendre nodes at which the lobe is the lobe's own nodes
// with c replaced by the node's position, a formula in the parameter.
#include "closed_form.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "fitting.h"
#include "specula/expr/expr.h"
#include "specula/expr/simplify.h"

namespace specula::design {

namespace {

using expr::Node;
using expr::Op;
using Nodes = std::vector<Node>;

constexpr int kMaxDegree = 2 * kMaxNodes - 1 - 3;  // the nh weight (2x² − 1)4x has degree 3
constexpr std::size_t kMaxLength = 4096, kMaxDepth = 64;
constexpr std::uint32_t kC = 0, kParam = 1;  // variable indices

Node number(double v) { return {Op::constant, 0, v}; }
bool same(const Nodes& a, const Nodes& b) {
  return std::ranges::equal(a, b, [](const Node& x, const Node& y) {
    return x.op == y.op && x.var == y.var && x.value == y.value && x.numerator == y.numerator &&
           x.denominator == y.denominator && x.symbol == y.symbol;
  });
}
Node op(Op o) { return {o, 0, 0}; }
Nodes cat(std::initializer_list<const Nodes*> parts, std::initializer_list<Op> ops) {
  Nodes out;
  for (const Nodes* p : parts) out.insert(out.end(), p->begin(), p->end());
  for (Op o : ops) out.push_back(op(o));
  return out;
}

/// A lobe's nodes as a tree: the start of the subtree that ends at each node.
class Tree {
 public:
  explicit Tree(Nodes nodes) : nodes_(std::move(nodes)), start_(nodes_.size()) {
    std::vector<std::size_t> stack;
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
      std::size_t first = i;
      for (int k = 0; k < expr::arity(nodes_[i].op); ++k) {
        first = stack.back();
        stack.pop_back();
      }
      start_[i] = first;
      stack.push_back(first);
    }
  }
  std::size_t root() const { return nodes_.size() - 1; }
  const Node& at(std::size_t i) const { return nodes_[i]; }
  std::size_t right(std::size_t i) const { return i - 1; }
  std::size_t left(std::size_t i) const { return expr::arity(nodes_[i].op) == 2 ? start_[i - 1] - 1 : i - 1; }
  Nodes subtree(std::size_t i) const { return {nodes_.begin() + static_cast<std::ptrdiff_t>(start_[i]), nodes_.begin() + static_cast<std::ptrdiff_t>(i) + 1}; }
  bool is_zero(std::size_t i) const { return nodes_[i].op == Op::constant && nodes_[i].value == 0; }

  /// The clamp at node i: max(X, 0) or max(0, X); the index of X, else nullopt.
  std::optional<std::size_t> clamp_argument(std::size_t i) const {
    if (nodes_[i].op != Op::max) return std::nullopt;
    if (is_zero(right(i))) return left(i);
    if (is_zero(left(i))) return right(i);
    return std::nullopt;
  }

 private:
  Nodes nodes_;
  std::vector<std::size_t> start_;
};

/// The degree in c of the subtree at i, clamps read as their argument; nullopt when it is no
/// polynomial in c, or holds clamps of two different arguments (`clamped` keeps the one seen).
std::optional<int> degree(const Tree& t, std::size_t i, std::optional<Nodes>& clamped) {
  const Node& n = t.at(i);
  if (n.op == Op::constant) return 0;
  if (n.op == Op::variable) return n.var == kC ? 1 : 0;
  if (const auto x = t.clamp_argument(i)) {
    const auto d = degree(t, *x, clamped);
    if (d == 0) return 0;  // max(g(p), 0): a function of the parameter
    if (d != 1) return std::nullopt;
    const Nodes argument = t.subtree(*x);
    if (clamped && !same(*clamped, argument)) return std::nullopt;
    clamped = argument;
    return 1;
  }
  const auto l = degree(t, t.left(i), clamped);
  if (!l) return std::nullopt;
  if (expr::arity(n.op) == 1) return n.op == Op::neg || *l == 0 ? l : std::nullopt;
  const auto r = degree(t, t.right(i), clamped);
  if (!r) return std::nullopt;
  std::optional<int> out;
  if (n.op == Op::add || n.op == Op::sub) {
    out = std::max(*l, *r);
  } else if (n.op == Op::mul) {
    out = *l + *r;
  } else if (n.op == Op::div) {
    if (*r == 0) out = l;
  } else if (n.op == Op::pow && *l > 0) {
    const Node& e = t.at(t.right(i));
    if (e.op == Op::constant && e.value >= 0 && e.value <= kMaxDegree && e.value == std::floor(e.value))
      out = *l * static_cast<int>(e.value);
  } else if (*l == 0 && *r == 0) {  // pow, min, max of the parameter alone
    out = 0;
  }
  return out && *out <= kMaxDegree ? out : std::nullopt;
}

/// The subtree at i with c replaced by `c_nodes` and every clamp by its argument (on) or 0 (off).
void emit(const Tree& t, std::size_t i, const Nodes& c_nodes, bool on, Nodes& out) {
  const Node& n = t.at(i);
  if (n.op == Op::variable && n.var == kC) {
    out.insert(out.end(), c_nodes.begin(), c_nodes.end());
    return;
  }
  if (const auto x = t.clamp_argument(i); x && [&] { std::optional<Nodes> ignored; return degree(t, *x, ignored) == 1; }()) {
    if (on) emit(t, *x, c_nodes, on, out);
    else out.push_back(number(0));
    return;
  }
  const int a = expr::arity(n.op);
  if (a == 2) emit(t, t.left(i), c_nodes, on, out);
  if (a >= 1) emit(t, t.right(i), c_nodes, on, out);
  out.push_back(n);
}

Nodes substituted(const Tree& t, const Nodes& c_nodes, bool on) {
  Nodes out;
  emit(t, t.root(), c_nodes, on, out);
  return out;
}

/// Gauss–Legendre on [−1, 1]: m nodes and weights (Newton's iteration on P_m from the usual
/// starting guesses; exact for polynomials of degree ≤ 2m − 1).
std::pair<std::vector<double>, std::vector<double>> gauss_legendre(int m) {
  std::vector<double> x(static_cast<std::size_t>(m)), w(static_cast<std::size_t>(m));
  for (int i = 0; i < m; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (m + 0.5)), dp = 0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = z;  // P_0, P_1, then up to P_m by the three-term recurrence
      for (int k = 2; k <= m; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = m * (z * p1 - p0) / (z * z - 1);
      const double step = p1 / dp;
      z -= step;
      if (std::abs(step) < 1e-16) break;
    }
    x[static_cast<std::size_t>(i)] = z;
    w[static_cast<std::size_t>(i)] = 2 / ((1 - z * z) * dp * dp);
  }
  return {x, w};
}

/// ∫ from a to b of F(x)·weight(x) dx, F's nodes with c := x (on or off the clamp), as nodes.
Nodes integral(const Tree& t, bool on, const Nodes& a, const Nodes& b, int nodes, Form form) {
  const auto [xi, wi] = gauss_legendre(nodes);
  const Nodes middle = cat({&a, &b}, {Op::add}), half = cat({&b, &a}, {Op::sub});
  Nodes sum;
  for (std::size_t j = 0; j < xi.size(); ++j) {
    // x = (a + b)/2 + (b − a)/2 · ξ
    Nodes x = middle;
    x.insert(x.end(), {number(0.5), op(Op::mul)});
    x.insert(x.end(), half.begin(), half.end());
    x.insert(x.end(), {number(0.5 * xi[j]), op(Op::mul), op(Op::add)});
    Nodes term = substituted(t, x, on);
    term.insert(term.end(), x.begin(), x.end());
    term.push_back(op(Op::mul));  // F(x)·x
    if (form == Form::nh) {       // ·(2x² − 1)·4
      term.insert(term.end(), x.begin(), x.end());
      term.insert(term.end(), x.begin(), x.end());
      term.insert(term.end(), {op(Op::mul), number(8), op(Op::mul), number(4), op(Op::sub), op(Op::mul)});
    }
    term.insert(term.end(), {number(wi[j]), op(Op::mul)});
    sum.insert(sum.end(), term.begin(), term.end());
    if (j > 0) sum.push_back(op(Op::add));
  }
  sum.insert(sum.end(), half.begin(), half.end());
  sum.insert(sum.end(), {number(0.5), op(Op::mul), op(Op::mul)});
  return sum;
}

bool vanishes(const Tree& t, const Settings& s) {  // F off the clamp ≡ 0 (the clamp is outermost)
  const expr::Expression off(substituted(t, {{Op::variable, kC, 0}}, false), {"c", s.param});
  for (double p : param_grid(s.lo, s.hi, 5))
    for (double c : {0.0, 0.3, 0.7, 1.0})
      if (expr::evaluate(off, std::vector<double>{c, p}) != 0) return false;
  return true;
}

}  // namespace

std::optional<std::string> closed_form_k(const std::string& formula, const Settings& s) {
  const expr::Expression lobe = expr::parse(formula, {"c", s.param});
  const Tree t({lobe.nodes().begin(), lobe.nodes().end()});
  std::optional<Nodes> clamped;
  const auto d = degree(t, t.root(), clamped);
  if (!d) return std::nullopt;
  const Form form = target_form(s);
  const int nodes = (*d + (form == Form::nh ? 3 : 1)) / 2 + 1;  // 2·nodes − 1 ≥ degree of F·weight
  const Nodes lower{form == Form::nh ? number(std::sqrt(0.5)) : number(0)}, one{number(1)};
  Nodes albedo;
  if (!clamped) {
    albedo = integral(t, true, lower, one, nodes, form);
  } else {
    // X = α c + β: β = X(0), α = X(1) − X(0); the kink c₀ = −β/α, clamped to [lower, 1].
    const Tree x(*clamped);
    const Nodes beta = substituted(x, {number(0)}, true), at_one = substituted(x, {number(1)}, true);
    const Nodes alpha = cat({&at_one, &beta}, {Op::sub});
    const expr::Expression alpha_e(alpha, {"c", s.param});
    int sign = 0;
    for (double p : param_grid(s.lo, s.hi, 257)) {
      const double a = expr::evaluate(alpha_e, std::vector<double>{0, p});
      const int here = a > 0 ? 1 : a < 0 ? -1 : 0;
      if (here == 0 || (sign != 0 && here != sign)) return std::nullopt;
      sign = here;
    }
    Nodes kink = cat({&beta, &alpha}, {Op::div, Op::neg});
    kink = cat({&kink, &lower}, {Op::max});
    kink = cat({&kink, &one}, {Op::min});
    const Nodes& on_from = sign > 0 ? kink : lower;
    const Nodes& on_to = sign > 0 ? one : kink;
    albedo = integral(t, true, on_from, on_to, nodes, form);
    if (!vanishes(t, s)) {
      const Nodes off = integral(t, false, sign > 0 ? lower : kink, sign > 0 ? kink : one, nodes, form);
      albedo = cat({&albedo, &off}, {Op::add});
    }
  }
  Nodes k{number(1), number(2 * std::numbers::pi)};
  k.insert(k.end(), albedo.begin(), albedo.end());
  k.insert(k.end(), {op(Op::mul), op(Op::div)});
  const expr::Expression full(k, {"c", s.param});
  expr::Expression shortest = expr::simplify(full);
  if (expr::to_infix(full).size() < expr::to_infix(shortest).size()) shortest = full;
  const std::string text = expr::to_infix(shortest);
  if (text.size() > kMaxLength || shortest.stack_depth() > kMaxDepth) return std::nullopt;
  return text;
}

}  // namespace specula::design
