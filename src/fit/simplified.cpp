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

bool allowed(const Genome& g, const SimplifyRules& rules) {
  return std::all_of(g.begin(), g.end(), [&](const expr::Node& n) { return allowed(n, rules); });
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

std::optional<Genome> simplified(const Genome& g, std::span<const double> predicted, const Rows& rows,
                                 const SimplifyRules& rules) {
  const expr::Expression simple = expr::simplify(expr::Expression(g, slot_names(rows.columns.size())));
  Genome out(simple.nodes().begin(), simple.nodes().end());
  if (expr::same_nodes(out, g) || rules.weights.of(out) > rules.weights.of(g) || !allowed(out, rules)) return std::nullopt;
  std::vector<double> values(predicted.size());
  expr::evaluate_batch(simple, rows.columns, values);
  if (!expr::values_agree(values, predicted)) return std::nullopt;
  return out;
}

}  // namespace specula::fit
