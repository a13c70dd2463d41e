// The engines' own forms as shapes: every maximal subexpression that reads no per-pixel variable
// (a number, or a formula in the per-material parameter such as 1 − α) becomes one free constant;
// exact integers stay as written.
#include "seeds.h"

#include "fitting.h"
#include "specula/expr/simplify.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fmt/format.h>

namespace specula::design {
namespace {

using expr::Node;
using expr::Op;

// The cost model's units of one node of a formula (operation_cost; an integer power by squaring).
int node_cost(const Node& n, const Node* exponent) {
  switch (n.op) {
    case Op::constant:
    case Op::variable: return 0;
    case Op::div: return operation_cost(Operation::div);
    case Op::sqrt: return operation_cost(Operation::sqrt);
    case Op::pow:
      if (exponent && expr::is_exact(*exponent) && exponent->value == std::round(exponent->value) && exponent->value >= 1 &&
          exponent->value <= 32) {
        const int k = static_cast<int>(exponent->value);
        return std::bit_width(static_cast<unsigned>(k)) - 1 + std::popcount(static_cast<unsigned>(k)) - 1;
      }
      return 2 * operation_cost(Operation::exp);
    case Op::exp:
    case Op::expm1: return operation_cost(Operation::exp);
    case Op::log:
    case Op::log2:
    case Op::log1p: return operation_cost(Operation::log2);
    case Op::sin:
    case Op::cos:
    case Op::acos:
    case Op::asin: return 2 * operation_cost(Operation::exp);
    default: return 1;
  }
}

// An integer as written (an exponent, a factor 2, the 1 of 1 − c): kept, not freed.
bool is_integer(const Node& n) {
  if (n.op != Op::constant) return false;
  if (expr::is_exact(n)) return n.denominator == 1 && n.symbol == expr::Symbol::one;
  return n.value == std::round(n.value) && std::abs(n.value) <= 1024;
}

// The closest rational a/b to x with b ≤ 255 and |a| < 2¹⁵ (continued fractions), as an exact constant.
Node rational_near(double x) {
  long p0 = 0, q0 = 1, p1 = 1, q1 = 0;
  double rest = x;
  for (int step = 0; step < 32; ++step) {
    const double whole = std::floor(rest);
    const long p2 = static_cast<long>(whole) * p1 + p0, q2 = static_cast<long>(whole) * q1 + q0;
    if (q2 > 255 || std::abs(p2) >= 32768) break;
    p0 = p1, q0 = q1, p1 = p2, q1 = q2;
    if (rest - whole < 1e-12) break;
    rest = 1 / (rest - whole);
  }
  if (q1 == 0) return expr::exact_constant(0, 1, expr::Symbol::one);
  return expr::exact_constant(static_cast<int>(p1), static_cast<int>(q1), expr::Symbol::one);
}

// The form printed with every free constant as 7: its structure.
std::string structure(const Shape& form, const std::vector<std::string>& names) {
  std::vector<Node> printed = form.nodes;
  for (auto& n : printed)
    if (n.op == Op::constant && !expr::is_exact(n)) n.value = 7;
  return expr::to_infix(expr::Expression(std::move(printed), names));
}

// The form simplified (expr::simplify: x·0, x·1 and x + 0 gone, constants folded) where that
// leaves fewer nodes; its cost and constants counted again.
Shape simplified(Shape form, const std::vector<std::string>& names) {
  const expr::Expression e = expr::simplify(form.expression(names));
  if (e.nodes().size() >= form.nodes.size()) return form;
  Shape out = form;
  out.nodes.assign(e.nodes().begin(), e.nodes().end());
  out.constants = 0;
  out.cost = 0;
  for (std::size_t i = 0; i < out.nodes.size(); ++i) {
    const Node& n = out.nodes[i];
    out.constants += n.op == Op::constant && !expr::is_exact(n);
    out.cost += node_cost(n, n.op == Op::pow ? &out.nodes[i - 1] : nullptr);
  }
  return out;
}

}  // namespace

namespace {

// Which of `values` (the form's free constants; only those `among` marks, if given) move the form
// in a direction the ones before them do not: the Jacobian's columns on `columns`, Gram–Schmidt in
// order, a column within 1e-5 (relative) of the span before it is redundant. Empty where the form
// is not finite there.
std::vector<bool> independent_constants(const Shape& form, const std::vector<double>& values,
                                        const std::vector<std::vector<double>>& columns, const std::vector<std::string>& names,
                                        const std::vector<bool>& among = {}) {
  const auto at = [&](const std::vector<double>& constants) {
    return evaluate_rows(with_constants(form, constants, names), columns);
  };
  const std::vector<double> base = at(values);
  if (!std::ranges::all_of(base, [](double x) { return std::isfinite(x); })) return {};
  std::vector<std::vector<double>> basis;  // orthonormal columns kept so far
  std::vector<bool> out(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (!among.empty() && !among[k]) continue;
    std::vector<double> moved = values;
    const double h = 1e-6 * std::max(1.0, std::abs(values[k]));
    moved[k] += h;
    const std::vector<double> after = at(moved);
    std::vector<double> column(base.size());
    double norm = 0;
    for (std::size_t r = 0; r < base.size(); ++r) column[r] = (after[r] - base[r]) / h, norm += column[r] * column[r];
    if (!std::isfinite(norm) || norm == 0) continue;
    const double before = std::sqrt(norm);
    for (const auto& b : basis) {
      double dot = 0;
      for (std::size_t r = 0; r < column.size(); ++r) dot += b[r] * column[r];
      for (std::size_t r = 0; r < column.size(); ++r) column[r] -= dot * b[r];
    }
    norm = 0;
    for (double x : column) norm += x * x;
    norm = std::sqrt(norm);
    if (norm <= 1e-5 * before) continue;
    for (double& x : column) x /= norm;
    basis.push_back(std::move(column));
    out[k] = true;
  }
  return out;
}

}  // namespace

Shape without_redundant_constants(Shape form, std::size_t per_pixel) {
  constexpr int kPoints = 96;
  std::vector<std::vector<double>> columns(per_pixel);
  std::uint64_t state = 0x9e3779b97f4a7c15;
  for (int i = 0; i < kPoints; ++i)
    for (auto& column : columns) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      column.push_back((static_cast<double>(state >> 11) + 1) * 0x1p-53);
    }
  std::vector<std::string> names;
  for (std::size_t v = 0; v < per_pixel; ++v) names.push_back(fmt::format("v{}", v));
  std::vector<double> values;
  for (const Node& n : form.nodes)
    if (n.op == Op::constant && !expr::is_exact(n)) values.push_back(n.value);
  const std::vector<bool> kept = independent_constants(form, values, columns, names);
  if (kept.empty()) return form;
  const auto rank = [](const std::vector<bool>& v) { return std::ranges::count(v, true); };
  // Each redundant constant held at 0 or 1 where the kept ones still span as much (the term it
  // scales or shifts then drops out: x·(y·a + b) + y·(x·c + d) with c = 0 is x·(y·a + b) + y·d),
  // else at a rational near its value.
  std::vector<Node> held(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (kept[k]) continue;
    held[k] = rational_near(values[k]);
    for (const int identity : {0, 1}) {
      std::vector<double> trial = values;
      trial[k] = identity;
      const std::vector<bool> still = independent_constants(form, trial, columns, names, kept);
      if (!still.empty() && rank(still) == rank(kept)) {
        values[k] = identity;
        held[k] = expr::exact_constant(identity, 1, expr::Symbol::one);
        break;
      }
    }
  }
  std::size_t k = 0;
  for (Node& n : form.nodes)
    if (n.op == Op::constant && !expr::is_exact(n)) {
      if (!kept[k]) {
        n = held[k];
        --form.constants;
      }
      ++k;
    }
  return simplified(std::move(form), names);
}

Shape freed_form(const expr::Expression& e, std::size_t per_pixel, double param) {
  const auto nodes = e.nodes();
  const std::size_t count = nodes.size();
  std::vector<std::size_t> start(count);  // the first node of each node's subtree
  std::vector<bool> uniform(count);       // reads no per-pixel variable
  for (std::size_t i = 0; i < count; ++i) {
    const Node& n = nodes[i];
    switch (expr::arity(n.op)) {
      case 0:
        start[i] = i;
        uniform[i] = n.op == Op::constant || n.var >= per_pixel;
        break;
      case 1:
        start[i] = start[i - 1];
        uniform[i] = uniform[i - 1];
        break;
      default: {
        const std::size_t left = start[i - 1] - 1;
        start[i] = start[left];
        uniform[i] = uniform[left] && uniform[i - 1];
      }
    }
  }
  std::vector<double> point(e.variables().size(), param);
  Shape out;
  std::vector<Node> form;
  // Emits the subtree ending at i: a free constant where it reads no per-pixel variable.
  const auto emit = [&](auto& self, std::size_t i) -> void {
    const Node& n = nodes[i];
    if (uniform[i] && !is_integer(n)) {
      const expr::Expression sub(std::vector<Node>(nodes.begin() + static_cast<std::ptrdiff_t>(start[i]),
                                                   nodes.begin() + static_cast<std::ptrdiff_t>(i) + 1),
                                 e.variables());
      form.push_back({Op::constant, 0, expr::evaluate(sub, point)});
      ++out.constants;
      return;
    }
    const int arity = expr::arity(n.op);
    if (arity >= 2) self(self, start[i - 1] - 1);
    if (arity >= 1) self(self, i - 1);
    out.cost += node_cost(n, arity == 2 && n.op == Op::pow ? &nodes[i - 1] : nullptr);
    // A kept integer as an exact constant: the fits hold those fixed.
    form.push_back(is_integer(n) ? expr::exact_constant(static_cast<int>(n.value), 1, expr::Symbol::one) : n);
  };
  emit(emit, count - 1);
  out.nodes = std::move(form);
  out.key = structure(out, {e.variables().begin(), e.variables().begin() + static_cast<std::ptrdiff_t>(per_pixel)});
  return out;
}

std::vector<Seed> reference_seeds(const Settings& s) {
  std::vector<Seed> out;
  if (!is_function_target(s.target)) return out;
  for (const TermReference& r : term_references()) {
    if (r.term != s.target || r.id == "exact") continue;
    Shape form = without_redundant_constants(freed_form(function_expression(s, r.formula), s.variables.size(), s.lo),
                                             s.variables.size());
    if (form.constants == 0 || form.constants > kMaxSeedConstants || form.cost > Ranges::member_cost) continue;
    form.key = fmt::format("{}'s form: {}", r.id, structure(form, s.variables));
    out.push_back({std::string(r.id), std::move(form)});
  }
  return out;
}

}  // namespace specula::design
