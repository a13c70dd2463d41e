#include "simplified.h"

#include <algorithm>
#include <bit>
#include <cstdint>
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

bool same_nodes(const Genome& a, const Genome& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const expr::Node& x, const expr::Node& y) {
    return x.op == y.op && x.var == y.var && std::bit_cast<std::uint64_t>(x.value) == std::bit_cast<std::uint64_t>(y.value);
  });
}

/// True if `values` are within 1e-12 relative of `predicted` (non-finite ones equal).
bool same_values(std::span<const double> values, std::span<const double> predicted) {
  for (std::size_t r = 0; r < values.size(); ++r) {
    const double a = values[r], b = predicted[r];
    if (!std::isfinite(a) || !std::isfinite(b)) {
      if (!(a == b) && !(std::isnan(a) && std::isnan(b))) return false;
    } else if (std::abs(a - b) > 1e-12 * std::max(std::abs(a), std::abs(b))) {
      return false;
    }
  }
  return true;
}

}  // namespace

std::optional<Genome> simplified(const Genome& g, std::span<const double> predicted, const Rows& rows,
                                 const SimplifyRules& rules) {
  std::vector<std::string> names;
  for (std::size_t v = 0; v < rows.columns.size(); ++v) names.push_back(fmt::format("v{}", v));
  const expr::Expression simple = expr::simplify(expr::Expression(g, names));
  Genome out(simple.nodes().begin(), simple.nodes().end());
  if (same_nodes(out, g) || rules.weights.of(out) > rules.weights.of(g) || !allowed(out, rules)) return std::nullopt;
  std::vector<double> values(predicted.size());
  expr::evaluate_batch(simple, rows.columns, values);
  if (!same_values(values, predicted)) return std::nullopt;
  return out;
}

}  // namespace specula::fit
