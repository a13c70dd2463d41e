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

// The rows with their inputs rounded as a shader gets them.
std::vector<Samples> rounded_inputs(std::span<const Samples> rows, Precision precision) {
  std::vector<Samples> out(rows.begin(), rows.end());
  for (Samples& g : out)
    for (auto& column : g.x)
      for (double& x : column) x = round_to(x, precision);
  return out;
}

// The objective's largest error of `evaluate` on the rows.
double rows_error(const RoundedEvaluator& evaluate, std::span<const Samples> rows, const Settings& s) {
  std::vector<double> point(s.variables.size() + (s.param.empty() ? 0 : 1));
  double worst = 0;
  for (const Samples& g : rows) {
    if (!s.param.empty()) point.back() = g.param;
    for (std::size_t r = 0; r < g.value.size(); ++r) {
      for (std::size_t v = 0; v < s.variables.size(); ++v) point[v] = g.x[v][r];
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
    : nodes_(e.nodes().begin(), e.nodes().end()), variables_(e.variables()), precision_(precision),
      stack_(nodes_.size()) {
  // A uniform reads the parameter and no per-pixel variable; numbers alone are literals.
  const auto& nodes = nodes_;
  std::vector<std::size_t> open;  // the nodes whose consumer is not read yet
  std::vector<std::size_t> parent(nodes.size(), nodes.size());
  std::vector<bool> pixel(nodes.size()), param(nodes.size()), uniform(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    pixel[i] = nodes[i].op == Op::variable && nodes[i].var < per_pixel_variables;
    param[i] = nodes[i].op == Op::variable && nodes[i].var >= per_pixel_variables;
    for (int k = 0; k < expr::arity(nodes[i].op); ++k) {
      pixel[i] = pixel[i] || pixel[open.back()];
      param[i] = param[i] || param[open.back()];
      parent[open.back()] = i;
      open.pop_back();
    }
    uniform[i] = param[i] && !pixel[i];
    open.push_back(i);
  }
  // Inside a uniform (below its top): computed in double with it. Parents come after children.
  std::vector<bool> inside(nodes.size());
  for (std::size_t i = nodes.size(); i-- > 0;)
    inside[i] = parent[i] < nodes.size() && (uniform[parent[i]] || inside[parent[i]]);
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
  const auto& nodes = nodes_;
  std::vector<double>& stack = stack_;
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
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    if (literal_[i]) out.push_back(i);
  return out;
}

void round_member(Lobe& l, std::span<const Samples> rows, const Settings& s, double claim) {
  RoundedEvaluator member(function_expression(s, l.formula), s.variables.size(), s.precision);
  const std::vector<Samples> inputs = rounded_inputs(rows, s.precision);
  const auto error = [&] { return rows_error(member, inputs, s); };
  const std::vector<std::size_t> literals = member.literals();
  for (std::size_t i : literals) member.set_literal(i, round_to(member.literal(i), s.precision));
  double best = error();
  for (int pass = 0; pass < kPasses; ++pass) {
    bool moved = false;
    for (std::size_t i : literals)
      for (int direction : {1, -1})
        for (int step = 0; step < kStepsPerPass; ++step) {
          const double kept = member.literal(i);
          member.set_literal(i, next_in(kept, direction, s.precision));
          const double e = error();
          if (!(e < best)) {
            member.set_literal(i, kept);
            break;
          }
          best = e;
          moved = true;
        }
    if (!moved) break;
  }
  l.formula = expr::to_infix(member.expression());
  l.precision_error = best;
  l.precision_note = best > claim * (1 + 1e-9)
                         ? fmt::format("in {} its largest error on the fits' rows is {:.6g}, past the {:.6g} it had before "
                                       "its constants were rounded", to_string(s.precision), best, claim)
                         : std::string();
}

}  // namespace specula::design
