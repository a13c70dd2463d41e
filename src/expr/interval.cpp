// Interval enclosures of the expression ops (include/specula/expr/interval.h).
#include "specula/expr/interval.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace specula::expr {
namespace {

constexpr Interval kWhole{-INFINITY, INFINITY};
constexpr int kOutwardUlps = 4;

// [lo, hi] moved outward by kOutwardUlps; NaN anywhere gives the whole line.
Interval outward(double lo, double hi) {
  if (std::isnan(lo) || std::isnan(hi)) return kWhole;
  for (int i = 0; i < kOutwardUlps; ++i) {
    lo = std::nextafter(lo, -INFINITY);
    hi = std::nextafter(hi, INFINITY);
  }
  return {lo, hi};
}

// An increasing function's enclosure.
template <class F>
Interval increasing(F f, Interval a) { return outward(f(a.lo), f(a.hi)); }

Interval product(Interval a, Interval b) {
  const double p[] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  if (std::ranges::any_of(p, [](double x) { return std::isnan(x); })) return kWhole;  // 0·∞
  return outward(*std::ranges::min_element(p), *std::ranges::max_element(p));
}

Interval quotient(Interval a, Interval b) {
  if (b.lo <= 0 && b.hi >= 0) return kWhole;
  return product(a, outward(1 / b.hi, 1 / b.lo));
}

// x^k for an integer k.
Interval integer_power(Interval a, int k) {
  if (k == 0) return {1, 1};
  if (k < 0) return quotient({1, 1}, integer_power(a, -k));
  const double lo = std::pow(a.lo, k), hi = std::pow(a.hi, k);
  if (k % 2 == 1) return outward(lo, hi);
  const Interval even = a.lo <= 0 && a.hi >= 0 ? outward(0, std::max(lo, hi)) : outward(std::min(lo, hi), std::max(lo, hi));
  return {std::max(even.lo, 0.0), even.hi};  // an even power is never negative
}

Interval power(Interval a, Interval b) {
  if (b.lo == b.hi && b.lo == std::round(b.lo) && std::abs(b.lo) <= 1024) return integer_power(a, static_cast<int>(b.lo));
  if (a.lo < 0) return kWhole;  // a negative base to a non-integer power: NaN somewhere
  // x^y is monotone in x for each y and in y for each x > 0: its extremes are at the corners.
  const double p[] = {std::pow(a.lo, b.lo), std::pow(a.lo, b.hi), std::pow(a.hi, b.lo), std::pow(a.hi, b.hi)};
  if (std::ranges::any_of(p, [](double x) { return std::isnan(x); })) return kWhole;
  return outward(*std::ranges::min_element(p), *std::ranges::max_element(p));
}

// sin on [lo, hi]: the ends, and ±1 where a maximum (π/2 + 2kπ) or minimum (−π/2 + 2kπ) lies inside.
Interval sine(Interval a, double shift) {
  if (!(a.hi - a.lo < 2 * std::numbers::pi)) return {-1, 1};
  const double s0 = std::sin(a.lo + shift), s1 = std::sin(a.hi + shift);
  double lo = std::min(s0, s1), hi = std::max(s0, s1);
  const auto contains = [&](double phase) {  // some phase + 2kπ in [lo, hi] (shifted)
    const double k = std::ceil((a.lo + shift - phase) / (2 * std::numbers::pi));
    return phase + 2 * std::numbers::pi * k <= a.hi + shift;
  };
  if (contains(std::numbers::pi / 2)) hi = 1;
  if (contains(-std::numbers::pi / 2)) lo = -1;
  const Interval out = outward(lo, hi);
  return {std::max(out.lo, -1.0), std::min(out.hi, 1.0)};
}

Interval unary(Op op, Interval a) {
  switch (op) {
    case Op::neg: return {-a.hi, -a.lo};
    case Op::exp: return increasing([](double x) { return std::exp(x); }, a);
    case Op::expm1: return increasing([](double x) { return std::expm1(x); }, a);
    case Op::log:
    case Op::log2:
    case Op::log1p: {
      const double floor = op == Op::log1p ? -1 : 0;
      if (!(a.lo > floor)) return kWhole;
      if (op == Op::log) return increasing([](double x) { return std::log(x); }, a);
      if (op == Op::log2) return increasing([](double x) { return std::log2(x); }, a);
      return increasing([](double x) { return std::log1p(x); }, a);
    }
    case Op::sqrt:
      if (!(a.lo >= 0)) return kWhole;
      return {std::sqrt(a.lo) == 0 ? 0.0 : outward(std::sqrt(a.lo), 0).lo, outward(0, std::sqrt(a.hi)).hi};
    case Op::abs:
      if (a.lo >= 0) return a;
      if (a.hi <= 0) return {-a.hi, -a.lo};
      return {0, std::max(-a.lo, a.hi)};
    case Op::sin: return sine(a, 0);
    case Op::cos: return sine(a, std::numbers::pi / 2);
    case Op::asin:
      if (!(a.lo >= -1 && a.hi <= 1)) return kWhole;
      return increasing([](double x) { return std::asin(x); }, a);
    case Op::acos:
      if (!(a.lo >= -1 && a.hi <= 1)) return kWhole;
      return outward(std::acos(a.hi), std::acos(a.lo));
    default: return kWhole;
  }
}

Interval binary(Op op, Interval a, Interval b) {
  switch (op) {
    case Op::add: return outward(a.lo + b.lo, a.hi + b.hi);
    case Op::sub: return outward(a.lo - b.hi, a.hi - b.lo);
    case Op::mul: return product(a, b);
    case Op::div: return quotient(a, b);
    case Op::pow: return power(a, b);
    case Op::min: return {std::min(a.lo, b.lo), std::min(a.hi, b.hi)};
    case Op::max: return {std::max(a.lo, b.lo), std::max(a.hi, b.hi)};
    default: return kWhole;
  }
}

Interval hull(Interval a, Interval b) { return {std::min(a.lo, b.lo), std::max(a.hi, b.hi)}; }
Interval plus(Interval a, Interval b) { return binary(Op::add, a, b); }
Interval times(Interval a, Interval b) { return binary(Op::mul, a, b); }
Interval over(Interval a, Interval b) { return binary(Op::div, a, b); }

// A value's enclosure and its gradient's, over the variables (forward mode).
struct Dual {
  Interval v;
  std::vector<Interval> d;
};

// d·k for every component.
std::vector<Interval> scaled(const std::vector<Interval>& d, Interval k) {
  std::vector<Interval> out(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) out[i] = times(d[i], k);
  return out;
}

Dual unary_dual(Op op, const Dual& a) {
  const Interval v = unary(op, a.v);
  switch (op) {
    case Op::neg: return {v, scaled(a.d, {-1, -1})};
    case Op::exp: return {v, scaled(a.d, v)};
    case Op::expm1: return {v, scaled(a.d, unary(Op::exp, a.v))};
    case Op::log: return {v, scaled(a.d, over({1, 1}, a.v))};
    case Op::log2: return {v, scaled(a.d, over({1, 1}, times(a.v, Interval::point(std::numbers::ln2))))};
    case Op::log1p: return {v, scaled(a.d, over({1, 1}, plus(a.v, {1, 1})))};
    case Op::sqrt: return {v, scaled(a.d, over({0.5, 0.5}, v))};
    case Op::abs: {
      if (a.v.lo >= 0) return {v, a.d};
      if (a.v.hi <= 0) return {v, scaled(a.d, {-1, -1})};
      return {v, scaled(a.d, {-1, 1})};
    }
    case Op::sin: return {v, scaled(a.d, unary(Op::cos, a.v))};
    case Op::cos: return {v, scaled(a.d, unary(Op::neg, unary(Op::sin, a.v)))};
    case Op::asin:
    case Op::acos: {
      const Interval k = over({1, 1}, unary(Op::sqrt, binary(Op::sub, {1, 1}, integer_power(a.v, 2))));
      return {v, scaled(a.d, op == Op::asin ? k : unary(Op::neg, k))};
    }
    default: return {kWhole, std::vector<Interval>(a.d.size(), kWhole)};
  }
}

Dual binary_dual(Op op, const Dual& a, const Dual& b) {
  const Interval v = binary(op, a.v, b.v);
  std::vector<Interval> d(a.d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    switch (op) {
      case Op::add: d[i] = plus(a.d[i], b.d[i]); break;
      case Op::sub: d[i] = binary(Op::sub, a.d[i], b.d[i]); break;
      case Op::mul: d[i] = plus(times(a.d[i], b.v), times(a.v, b.d[i])); break;
      case Op::div: d[i] = over(binary(Op::sub, a.d[i], times(v, b.d[i])), b.v); break;  // (a' − (a/b)·b')/b
      case Op::pow:
        if (b.v.lo == b.v.hi && b.d[i].lo == 0 && b.d[i].hi == 0 && b.v.lo == std::round(b.v.lo) && std::abs(b.v.lo) <= 1024) {
          const int k = static_cast<int>(b.v.lo);  // k·a^(k−1)·a'
          d[i] = times(times(Interval::point(k), integer_power(a.v, k - 1)), a.d[i]);
        } else {  // a^b·(b'·ln a + b·a'/a)
          d[i] = times(v, plus(times(b.d[i], unary(Op::log, a.v)), over(times(b.v, a.d[i]), a.v)));
        }
        break;
      case Op::min:
      case Op::max: {
        const bool a_below = a.v.hi <= b.v.lo, b_below = b.v.hi <= a.v.lo;
        const bool pick_a = op == Op::min ? a_below : b_below, pick_b = op == Op::min ? b_below : a_below;
        d[i] = pick_a ? a.d[i] : pick_b ? b.d[i] : hull(a.d[i], b.d[i]);
        break;
      }
      default: d[i] = kWhole;
    }
  }
  return {v, std::move(d)};
}

Interval intersection(Interval a, Interval b) { return {std::max(a.lo, b.lo), std::min(a.hi, b.hi)}; }

}  // namespace

Interval evaluate_mean_value(const Expression& e, std::span<const Interval> variables) {
  const std::size_t n = variables.size();
  std::vector<Dual> stack;
  stack.reserve(e.nodes().size());
  for (const Node& node : e.nodes()) {
    switch (arity(node.op)) {
      case 0: {
        Dual leaf{node.op == Op::constant ? Interval::point(node.value) : variables[node.var], std::vector<Interval>(n, {0, 0})};
        if (node.op == Op::variable) leaf.d[node.var] = {1, 1};
        stack.push_back(std::move(leaf));
        break;
      }
      case 1: stack.back() = unary_dual(node.op, stack.back()); break;
      default: {
        const Dual b = std::move(stack.back());
        stack.pop_back();
        stack.back() = binary_dual(node.op, stack.back(), b);
      }
    }
  }
  const Dual& f = stack.back();
  std::vector<Interval> centre(n);
  for (std::size_t i = 0; i < n; ++i) centre[i] = Interval::point((variables[i].lo + variables[i].hi) / 2);
  Interval mean_value = evaluate_interval(e, centre);
  for (std::size_t i = 0; i < n; ++i)
    mean_value = plus(mean_value, times(f.d[i], binary(Op::sub, variables[i], centre[i])));
  if (mean_value.whole() || std::isnan(mean_value.lo) || std::isnan(mean_value.hi)) return f.v;
  const Interval both = intersection(f.v, mean_value);
  return both.lo <= both.hi ? both : mean_value;
}

Interval evaluate_interval(const Expression& e, std::span<const Interval> variables) {
  std::vector<Interval> stack;
  stack.reserve(e.nodes().size());
  for (const Node& n : e.nodes()) {
    switch (arity(n.op)) {
      case 0: stack.push_back(n.op == Op::constant ? Interval::point(n.value) : variables[n.var]); break;
      case 1: stack.back() = unary(n.op, stack.back()); break;
      default: {
        const Interval b = stack.back();
        stack.pop_back();
        stack.back() = binary(n.op, stack.back(), b);
      }
    }
    if (std::isnan(stack.back().lo) || std::isnan(stack.back().hi)) stack.back() = kWhole;
  }
  return stack.back();
}

}  // namespace specula::expr
