#pragma once
// Interval arithmetic on expressions (docs/designer.md, "A certified bound"): for each variable an
// interval, the set of values the expression takes when each variable ranges over its interval is
// enclosed in the result. Every operation is computed at its interval's ends (or at the critical
// points inside: sin and cos at their extrema, x² at 0), each end moved outward by 4 ulp, which
// covers libm's error (under 1 ulp for exp, log, pow, sin, cos on glibc) and the rounding of the
// operations. Where an operand leaves an operation's domain (a divisor spanning 0, the log of a
// range reaching below 0), the result is the whole line [−∞, ∞]: an enclosure, never a wrong one.
#include <cmath>
#include <span>

#include "specula/expr/expr.h"

namespace specula::expr {

struct Interval {
  double lo = 0, hi = 0;
  static Interval point(double x) { return {x, x}; }
  bool whole() const { return !(lo > -INFINITY && hi < INFINITY); }
};

/// An interval holding every value `e` takes with variable i anywhere in variables[i].
Interval evaluate_interval(const Expression& e, std::span<const Interval> variables);

/// The same, tighter on small boxes: the natural enclosure above intersected with the mean-value
/// form f(m) + Σᵢ ∂f/∂xᵢ(X)·(Xᵢ − mᵢ), m the box's centre and the gradient's enclosure by forward
/// differentiation in interval arithmetic. Its overestimate shrinks with the square of the box's
/// width where the natural one shrinks with the width (Moore 1966).
Interval evaluate_mean_value(const Expression& e, std::span<const Interval> variables);

}  // namespace specula::expr
