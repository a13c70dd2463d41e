#include "simplified.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <string>

#include "specula/expr/simplify.h"

namespace specula::fit {
namespace {

using expr::Op;

bool allowed(const expr::Node& n, const SimplifyRules& rules) {
  if (n.op == Op::variable || n.op == Op::neg || n.op == Op::sub) return true;
  if (n.op == Op::constant)
    return rules.constants == Constants::fitted || (rules.constants == Constants::integer && n.value == std::round(n.value));
  return std::find(rules.operators.begin(), rules.operators.end(), n.op) != rules.operators.end();
}

bool has(const SimplifyRules& rules, Op op) {
  return std::find(rules.operators.begin(), rules.operators.end(), op) != rules.operators.end();
}

/// Every node allowed, or inside an elementary constant (an op over exact constants only, such as
/// 1/√(2π)): a constant, whichever operators write it; and a division by one is a product.
bool allowed(const Genome& g, const SimplifyRules& rules) {
  const std::vector<bool> exact = expr::exact_only_subtrees(g);
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (exact[i] && expr::arity(g[i].op) > 0) continue;
    const bool by_constant = g[i].op == Op::div && exact[i - 1] && has(rules, Op::mul);  // i − 1: the divisor's root
    if (!by_constant && !allowed(g[i], rules)) return false;
  }
  return true;
}

/// The integer power x^k the search may not write, as it may: x·x·…·x for 2 ≤ k ≤ kMaxExpanded,
/// 1/(x·…·x) for −kMaxExpanded ≤ k ≤ −1.
constexpr double kMaxExpanded = 4;

std::optional<int> expandable_exponent(const expr::Node& n, const SimplifyRules& rules) {
  if (!expr::is_exact(n) || n.value != std::round(n.value) || std::abs(n.value) > kMaxExpanded) return std::nullopt;
  const int k = static_cast<int>(n.value);
  if (k >= 2 && has(rules, Op::mul)) return k;
  if (k <= -1 && has(rules, Op::div) && (k == -1 || has(rules, Op::mul))) return k;
  return std::nullopt;
}

/// The subtree of `g` ending at `root`, written into `out` with its integer powers expanded.
void write_expanded(const Genome& g, const std::vector<std::size_t>& starts, std::size_t root,
                    const SimplifyRules& rules, Genome& out) {
  const expr::Node& n = g[root];
  const int arity = expr::arity(n.op);
  if (n.op == Op::pow) {
    const std::size_t base = starts[root - 1] - 1;
    if (const auto k = expandable_exponent(g[root - 1], rules)) {
      if (*k < 0) out.push_back(expr::Node{Op::constant, 0, 1.0, 1, 1});
      for (int i = 0; i < std::abs(*k); ++i) {
        write_expanded(g, starts, base, rules, out);
        if (i > 0) out.push_back(expr::Node{Op::mul, 0, 0});
      }
      if (*k < 0) out.push_back(expr::Node{Op::div, 0, 0});
      return;
    }
  }
  if (arity == 2) write_expanded(g, starts, starts[root - 1] - 1, rules, out);
  if (arity >= 1) write_expanded(g, starts, root - 1, rules, out);
  out.push_back(n);
}

/// `g` with the integer powers the simplifier made (x·x → x²) written back as products where the
/// search's operators have no ^: the rest of the simplification (signs, folding, order) is kept.
Genome powers_as_products(const Genome& g, const SimplifyRules& rules) {
  if (has(rules, Op::pow) || std::none_of(g.begin(), g.end(), [](const expr::Node& n) { return n.op == Op::pow; }))
    return g;
  Genome out;
  write_expanded(g, subtree_starts(g), g.size() - 1, rules, out);
  return out;
}

}  // namespace

std::vector<std::string> slot_names(std::size_t count) {
  std::vector<std::string> names;
  for (std::size_t v = 0; v < count; ++v) names.push_back(fmt::format("v{}", v));
  return names;
}

bool relies_on_cancellation(const Genome& g, const Rows& rows) {
  if (std::none_of(g.begin(), g.end(), [](const expr::Node& n) { return n.op == Op::constant; })) return false;
  const auto starts = subtree_starts(g);
  const auto names = slot_names(rows.columns.size());
  const double ratio = std::pow(10.0, kCancelledDigits);
  const auto operand = [&](std::size_t root) {
    return expr::Expression(Genome(g.begin() + static_cast<std::ptrdiff_t>(starts[root]), g.begin() + static_cast<std::ptrdiff_t>(root) + 1), names);
  };
  std::vector<double> row(rows.columns.size());
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (g[i].op != Op::add && g[i].op != Op::sub) continue;
    const std::size_t right = i - 1, left = starts[right] - 1;
    const expr::Expression a = operand(left), b = operand(right);
    bool everywhere = rows.size() > 0;
    for (std::size_t r = 0; r < rows.size() && everywhere; ++r) {
      for (std::size_t v = 0; v < row.size(); ++v) row[v] = rows.columns[v][r];
      const double x = expr::evaluate(a, row), y = expr::evaluate(b, row);
      everywhere = std::max(std::abs(x), std::abs(y)) > ratio * std::abs(g[i].op == Op::add ? x + y : x - y);
    }
    if (everywhere) return true;
  }
  return false;
}

std::vector<bool> positive_columns(std::span<const std::span<const double>> columns) {
  std::vector<bool> out;
  for (const auto& column : columns)
    out.push_back(!column.empty() && std::all_of(column.begin(), column.end(), [](double v) { return v > 0; }));
  return out;
}

std::optional<Genome> simplified(const Genome& g, std::span<const double> predicted, const Rows& rows,
                                 const SimplifyRules& rules) {
  const expr::Expression simple = expr::simplify(expr::Expression(g, slot_names(rows.columns.size())), rules.positive);
  Genome out = powers_as_products(Genome(simple.nodes().begin(), simple.nodes().end()), rules);
  if (expr::same_nodes(out, g) || rules.weights.of(out) > rules.weights.of(g) || !allowed(out, rules)) return std::nullopt;
  std::vector<double> values(predicted.size());
  expr::evaluate_batch(expr::Expression(out, slot_names(rows.columns.size())), rows.columns, values);
  if (!expr::values_agree(values, predicted)) return std::nullopt;
  return out;
}

}  // namespace specula::fit
