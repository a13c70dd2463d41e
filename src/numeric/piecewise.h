#pragma once
// Private: adaptive quadrature over [a, b] for integrands with a feature of size `width` at a
// (a narrow lobe) and kinks at known points. The integral runs in s = (x − a)/width, split at
// s = 1, 4, 16, … and at every breakpoint, with adaptive 31-point Gauss-Kronrod on each piece:
// every piece is O(1) long whatever the width, and no piece straddles a kink. The work limit
// (specula/interrupt) is checked every kEvaluationsPerCheck evaluations: one piece of an
// expensive integrand (a user's formula) may take up to 2^max_depth × 31 of them.
//
// The recursion is ours, not Boost's: Boost 1.74's compares an interval's |K31 − G15| on [−1, 1],
// not scaled by the interval's half-length, with a tolerance that is scaled, so its test tightens
// by that half-length and by 2 at each bisection until no double passes it: every interval it
// splits runs to max_depth. Here an interval is accepted when its scaled |K31 − G15| is within
// tolerance × |K31| or its share of its piece's allowance (halved at each bisection), or
// when it has reached the integrand's rounding noise (at_noise_floor): a finite-precision f, e.g.
// an albedo at grazing incidence, where V = 2(L·H)H − L holds H to ε/(L·H) only, has no accuracy
// left to find below it, and before, every interval there ran to max_depth.
#include <algorithm>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <vector>

#include "specula/interrupt/interrupt.h"

namespace specula::numeric {

struct Estimate {
  double value = 0;
  double error = 0;  ///< sum of the intervals' |K31 − G15|: an upper bound in practice
  std::size_t evaluations = 0;  ///< of the integrand
};

inline constexpr double kDefaultTolerance = 1e-13;
inline constexpr std::size_t kEvaluationsPerCheck = 256;
/// Rounding noise is small: an interval is at its noise floor only if its error is below this
/// share of ∫|f| over it (an unresolved feature of f is not noise).
inline constexpr double kNoiseCeiling = 1e-4;

namespace detail {

/// A (2m+1)-point Kronrod rule, the m-point Gauss rule it extends and ∫|f| over [a, b].
struct Rule {
  double kronrod = 0, gauss = 0, magnitude = 0;
  double error() const noexcept { return std::abs(kronrod - gauss); }
};

template <unsigned Points, class F>
Rule gauss_kronrod(const F& f, double a, double b) {
  using Kronrod = boost::math::quadrature::gauss_kronrod<double, Points>;
  using Gauss = boost::math::quadrature::gauss<double, Points / 2>;
  const auto& x = Kronrod::abscissa();  // 0 first; the even ones are the Gauss nodes
  const auto& wk = Kronrod::weights();
  const auto& wg = Gauss::weights();
  const double mid = (a + b) / 2, half = (b - a) / 2;
  const double centre = f(mid);
  Rule r{centre * wk[0], centre * wg[0], std::abs(centre) * wk[0]};
  for (std::size_t i = 1; i < x.size(); ++i) {
    const double lo = f(mid - half * x[i]), hi = f(mid + half * x[i]);
    r.kronrod += (lo + hi) * wk[i];
    r.magnitude += (std::abs(lo) + std::abs(hi)) * wk[i];
    if (i % 2 == 0) r.gauss += (lo + hi) * wg[i / 2];
  }
  return {r.kronrod * half, r.gauss * half, r.magnitude * half};
}

/// Bisection did not lower the error, both halves carry a share of it (a kink or a step leaves
/// one half clean) and it is small against ∫|f|: what is left is f's rounding noise.
inline bool at_noise_floor(const Rule& whole, const Rule& left, const Rule& right) noexcept {
  const double error = whole.error();
  return left.error() + right.error() >= error && std::min(left.error(), right.error()) >= error / 4 &&
         error <= kNoiseCeiling * whole.magnitude;
}

template <unsigned Points, class F>
Estimate refine(const F& f, double a, double b, const Rule& rule, double tolerance, double share, unsigned depth) {
  // A non-finite estimate (f inf or NaN, or a sum past the largest double) stays so in every half:
  // bisecting it would only run every level to max_depth.
  if (depth == 0 || !std::isfinite(rule.error()) || rule.error() <= std::max(share, tolerance * std::abs(rule.kronrod)))
    return {rule.kronrod, rule.error()};
  const double mid = (a + b) / 2;
  const Rule left = gauss_kronrod<Points>(f, a, mid), right = gauss_kronrod<Points>(f, mid, b);
  if (at_noise_floor(rule, left, right)) return {left.kronrod + right.kronrod, left.error() + right.error()};
  const Estimate l = refine<Points>(f, a, mid, left, tolerance, share / 2, depth - 1);
  const Estimate r = refine<Points>(f, mid, b, right, tolerance, share / 2, depth - 1);
  return {l.value + r.value, l.error + r.error};
}

}  // namespace detail

/// How each piece is integrated: over s itself, or over t ∈ [0, 1] with s = c0 + (c1 − c0)
/// sin²(πt/2), whose derivative vanishes at both ends, so that a root-type behaviour there,
/// (s − c0)^(k/2) (where a horizon or a kink enters the range), becomes smooth in t.
enum class Ends { plain, smoothed };

/// `Points`: the Kronrod rule on each interval, 31 (the default) or 15 (for short smooth pieces,
/// as the albedo's inner integrals between the kinks of a V-cavity G are).
template <unsigned Points = 31, class F>
Estimate integrate_pieces(const F& f, double a, double b, double width,
                          const std::vector<double>& breakpoints = {},
                          double tolerance = kDefaultTolerance, unsigned max_depth = 15, Ends ends = Ends::plain) {
  Estimate total;
  if (!(b > a)) return total;
  width = std::clamp(width, 1e-300, b - a);
  std::vector<double> cuts{0};
  for (double s = 1; a + s * width < b; s *= 4) cuts.push_back(s);
  for (const double x : breakpoints)
    if (x > a && x < b) cuts.push_back((x - a) / width);
  cuts.push_back((b - a) / width);
  std::sort(cuts.begin(), cuts.end());
  auto in_s = [&](double s) {
    if (++total.evaluations % kEvaluationsPerCheck == 0) check_interrupt();
    return f(a + s * width);
  };
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  const bool smoothed = ends == Ends::smoothed;
  // Piece i over [lo(i), hi(i)] in its own variable: s, or t for smoothed ends.
  auto lo = [&](std::size_t i) { return smoothed ? 0.0 : cuts[i]; };
  auto hi = [&](std::size_t i) { return smoothed ? 1.0 : cuts[i + 1]; };
  auto piece = [&](std::size_t i) {
    return [&in_s, smoothed, c0 = cuts[i], length = cuts[i + 1] - cuts[i]](double x) {
      if (!smoothed) return in_s(x);
      constexpr double kHalfPi = std::numbers::pi / 2;
      const double h = std::sin(kHalfPi * x);
      return in_s(c0 + length * h * h) * length * kHalfPi * std::sin(2 * kHalfPi * x);
    };
  };
  std::vector<detail::Rule> rules;
  double sum = 0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    rules.push_back(detail::gauss_kronrod<Points>(piece(i), lo(i), hi(i)));
    sum += rules.back().kronrod;
  }
  // A piece may err by tolerance × max(its own |K31|, |∑ K31| / pieces): one that weighs
  // nothing in the sum (a sliver between two breakpoints) is not refined for its own sake.
  const double even_part = std::abs(sum) / static_cast<double>(rules.size());
  for (std::size_t i = 0; i < rules.size(); ++i) {
    const double share = tolerance * std::max(std::abs(rules[i].kronrod), even_part);
    const Estimate part = detail::refine<Points>(piece(i), lo(i), hi(i), rules[i], tolerance, share, max_depth);
    total.value += part.value;
    total.error += part.error;
  }
  total.value *= width;
  total.error *= width;
  return total;
}

}  // namespace specula::numeric
