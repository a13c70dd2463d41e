#include "precision.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace specula::design {

using expr::Node;
using expr::Op;

namespace {

constexpr int kPasses = 4;
constexpr int kStepsPerPass = 16;  // ulps one constant may move in one pass

double half_quantum(double a) { return a < 0x1p-14 ? 0x1p-24 : std::ldexp(1.0, std::ilogb(a) - 10); }

double round_to_half(double x) {
  if (!std::isfinite(x) || x == 0) return x;
  const double quantum = half_quantum(std::abs(x));
  const double rounded = std::nearbyint(x / quantum) * quantum;  // the default rounding mode: ties to even
  return std::abs(rounded) > 65504 ? std::copysign(INFINITY, x) : rounded;
}

// The objective's largest error of `evaluate` on the rows, the inputs rounded as a shader gets them.
double rows_error(const RoundedEvaluator& evaluate, std::span<const Samples> rows, const Settings& s) {
  std::vector<double> point(s.variables.size() + (s.param.empty() ? 0 : 1));
  double worst = 0;
  for (const Samples& g : rows) {
    if (!s.param.empty()) point.back() = g.param;
    for (std::size_t r = 0; r < g.value.size(); ++r) {
      for (std::size_t v = 0; v < s.variables.size(); ++v) point[v] = round_to(g.x[v][r], s.precision);
      const double d = std::abs(evaluate(point) - g.value[r]);
      const double e = s.objective == Objective::max_rel ? d / g.value[r] : d;
      if (!(e <= worst)) worst = std::isnan(e) ? INFINITY : e;
    }
  }
  return worst;
}

}  // namespace

double round_to(double x, Precision precision) {
  switch (precision) {
    case Precision::f64: return x;
    case Precision::f32: return static_cast<double>(static_cast<float>(x));
    case Precision::f16: return round_to_half(x);
  }
  return x;
}

double next_in(double x, int direction, Precision precision) {
  const double toward = direction > 0 ? INFINITY : -INFINITY;
  switch (precision) {
    case Precision::f64: return std::nextafter(x, toward);
    case Precision::f32: return static_cast<double>(std::nextafter(static_cast<float>(x), static_cast<float>(toward)));
    case Precision::f16: {
      // Toward 0 from a power of two the next value is half a quantum away.
      const double a = std::abs(x), quantum = half_quantum(a);
      const bool toward_zero = x != 0 && (direction > 0) == (x < 0);
      const bool power = a > 0x1p-14 && a == std::ldexp(1.0, std::ilogb(a));
      return round_to_half(x + (direction > 0 ? 1 : -1) * (toward_zero && power ? quantum / 2 : quantum));
    }
  }
  return x;
}

RoundedEvaluator::RoundedEvaluator(const expr::Expression& e, std::size_t per_pixel_variables, Precision precision)
    : e_(e), per_pixel_(per_pixel_variables), precision_(precision) {
  // A uniform reads the parameter and no per-pixel variable; numbers alone are literals.
  const auto& nodes = e.nodes();
  std::vector<std::size_t> open;  // the nodes whose consumer is not read yet
  std::vector<std::size_t> parent(nodes.size(), nodes.size());
  std::vector<bool> pixel(nodes.size()), param(nodes.size());
  uniform_.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    pixel[i] = nodes[i].op == Op::variable && nodes[i].var < per_pixel_;
    param[i] = nodes[i].op == Op::variable && nodes[i].var >= per_pixel_;
    for (int k = 0; k < expr::arity(nodes[i].op); ++k) {
      pixel[i] = pixel[i] || pixel[open.back()];
      param[i] = param[i] || param[open.back()];
      parent[open.back()] = i;
      open.pop_back();
    }
    uniform_[i] = param[i] && !pixel[i];
    open.push_back(i);
  }
  // Inside a uniform (below its top): computed in double with it. Parents come after children.
  std::vector<bool> inside(nodes.size());
  for (std::size_t i = nodes.size(); i-- > 0;)
    inside[i] = parent[i] < nodes.size() && (uniform_[parent[i]] || inside[parent[i]]);
  round_here_.resize(nodes.size());
  literal_.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    round_here_[i] = !inside[i];
    // A fitted number a shader writes as a literal: not an integer (a power's 2, an exact 3), not
    // a power's exponent, not inside a uniform.
    const Node& n = nodes[i];
    const bool exponent = parent[i] < nodes.size() && nodes[parent[i]].op == Op::pow && i + 1 == parent[i];
    literal_[i] = n.op == Op::constant && !expr::is_exact(n) && n.value != std::round(n.value) && !exponent && !inside[i];
  }
}

double RoundedEvaluator::operator()(std::span<const double> point) const {
  const auto& nodes = e_.nodes();
  std::vector<double> stack(nodes.size());
  std::size_t top = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Node& n = nodes[i];
    double value = 0;
    switch (expr::arity(n.op)) {
      case 0: value = n.op == Op::constant ? n.value : point[n.var]; break;
      case 1: value = expr::apply(n.op, stack[--top]); break;
      default: {
        const double b = stack[--top], a = stack[--top];
        value = expr::apply(n.op, a, b);
      }
    }
    stack[top++] = round_here_[i] ? round_to(value, precision_) : value;
  }
  return stack[0];
}

std::vector<std::size_t> RoundedEvaluator::literals() const {
  std::vector<std::size_t> out;
  const auto& nodes = e_.nodes();
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (literal_[i]) out.push_back(i);
  return out;
}

void round_member(Lobe& l, std::span<const Samples> rows, const Settings& s, double claim) {
  const expr::Expression parsed = function_expression(s, l.formula);
  std::vector<Node> nodes(parsed.nodes().begin(), parsed.nodes().end());
  const std::vector<std::string> names = formula_variables(s);
  const auto error_of = [&](const std::vector<Node>& n) {
    return rows_error(RoundedEvaluator(expr::Expression(n, names), s.variables.size(), s.precision), rows, s);
  };
  const std::vector<std::size_t> literals = RoundedEvaluator(expr::Expression(nodes, names), s.variables.size(), s.precision).literals();
  for (std::size_t i : literals) nodes[i].value = round_to(nodes[i].value, s.precision);
  double best = error_of(nodes);
  for (int pass = 0; pass < kPasses; ++pass) {
    bool moved = false;
    for (std::size_t i : literals)
      for (int direction : {1, -1})
        for (int step = 0; step < kStepsPerPass; ++step) {
          const double kept = nodes[i].value;
          nodes[i].value = next_in(kept, direction, s.precision);
          const double e = error_of(nodes);
          if (!(e < best)) {
            nodes[i].value = kept;
            break;
          }
          best = e;
          moved = true;
        }
    if (!moved) break;
  }
  l.formula = expr::to_infix(expr::Expression(std::move(nodes), names));
  l.precision_error = best;
  l.precision_note = best > claim * (1 + 1e-9)
                         ? fmt::format("in {} its largest error on the fits' rows is {:.6g}, past the {:.6g} it had before "
                                       "its constants were rounded", to_string(s.precision), best, claim)
                         : std::string();
}

}  // namespace specula::design
