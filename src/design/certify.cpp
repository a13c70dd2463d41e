#include "certify.h"

#include <algorithm>
#include <cmath>
#include <queue>

#include "specula/expr/interval.h"
#include "specula/expr/simplify.h"

namespace specula::design {
namespace {

using expr::Interval;

struct Box {
  std::vector<Interval> sides;  // the per-pixel variables, then the parameter
  double upper = INFINITY;
  bool operator<(const Box& other) const { return upper < other.upper; }
};

// F − T in one expression: F's nodes, T's, and a subtraction.
expr::Expression difference(const expr::Expression& f, const expr::Expression& t) {
  std::vector<expr::Node> nodes(f.nodes().begin(), f.nodes().end());
  nodes.insert(nodes.end(), t.nodes().begin(), t.nodes().end());
  nodes.push_back({expr::Op::sub, 0, 0});
  return expr::Expression(std::move(nodes), f.variables());
}

}  // namespace

bool certifiable(const Settings& s) { return is_function_target(s.target) && !is_tabulated(s.target); }

Certified certify(const Settings& s, std::string_view formula, double known, const std::function<bool()>& stop) {
  Certified out;
  out.found = known;
  const expr::Expression f = function_expression(s, formula), t = function_expression(s);
  if (expr::same_nodes(f.nodes(), t.nodes())) {  // the term itself: no error anywhere
    out.bound = 0;
    return out;
  }
  const expr::Expression d = difference(f, t);
  const std::size_t k = s.variables.size();
  std::vector<Interval> domain(k, Interval{kCertifiedFloor, 1});
  if (!s.param.empty()) domain.push_back({s.lo, s.hi});
  // Widths compare in log scale where a side spans a factor of 4 or more (the per-pixel variables
  // down to 10⁻⁶: what happens near 0 happens on its own scale), else plain.
  std::vector<bool> logarithmic;
  for (const Interval& side : domain) logarithmic.push_back(log_spaced(side.lo, side.hi));
  const auto width = [&](const Interval& side, std::size_t v) {
    return logarithmic[v] ? std::log(side.hi / side.lo) : side.hi - side.lo;
  };
  std::vector<double> extent;
  for (std::size_t v = 0; v < domain.size(); ++v) extent.push_back(domain[v].hi > domain[v].lo ? width(domain[v], v) : 1);
  std::priority_queue<Box> boxes;
  std::vector<double> centre(domain.size());
  const auto examine = [&](std::vector<Interval> sides) {
    ++out.boxes;
    for (std::size_t v = 0; v < sides.size(); ++v) centre[v] = (sides[v].lo + sides[v].hi) / 2;
    const double at_centre = std::abs(expr::evaluate(d, centre));
    if (at_centre > out.found) out.found = at_centre, out.where = centre;
    const Interval e = expr::evaluate_mean_value(d, sides);
    const double upper = e.whole() ? INFINITY : std::max(std::abs(e.lo), std::abs(e.hi));
    boxes.push({std::move(sides), upper});
  };
  // The output index takes its values only: one starting box per value.
  for (int i = 0; i < output_count(s.target); ++i) {
    std::vector<Interval> start = domain;
    if (output_count(s.target) > 1) start[k - 1] = Interval::point(i);
    examine(std::move(start));
  }
  const auto close_enough = [&] { return boxes.top().upper <= out.found * (1 + kCertifyTolerance) + 1e-9; };
  while (!close_enough() && out.boxes < kMaxCertifyBoxes) {
    if (out.boxes % 4096 == 0 && stop()) break;
    Box box = boxes.top();
    boxes.pop();
    std::size_t widest = 0;
    for (std::size_t v = 1; v < box.sides.size(); ++v)
      if (width(box.sides[v], v) / extent[v] > width(box.sides[widest], widest) / extent[widest]) widest = v;
    const Interval& split = box.sides[widest];
    const double middle = logarithmic[widest] ? std::sqrt(split.lo * split.hi) : (split.lo + split.hi) / 2;
    std::vector<Interval> right = box.sides;
    box.sides[widest].hi = middle;
    right[widest].lo = middle;
    examine(std::move(box.sides));
    examine(std::move(right));
  }
  out.bound = std::max(boxes.top().upper, out.found);
  return out;
}

}  // namespace specula::design
