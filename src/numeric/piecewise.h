#pragma once
// Private: adaptive quadrature over [a, b] for integrands with a feature of size `width` at a
// (a narrow lobe) and kinks at known points. The integral runs in s = (x − a)/width, split at
// s = 1, 4, 16, … and at every breakpoint, with adaptive 31-point Gauss-Kronrod on each piece:
// every piece is O(1) long whatever the width (Boost's error control misbehaves on pieces of
// length 1e-9), and no piece straddles a kink. The work limit (specula/interrupt) is checked
// every kEvaluationsPerCheck evaluations: one piece of an expensive or noisy integrand (a user's
// formula) may take up to 2^max_depth × 31 of them.
#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <initializer_list>
#include <vector>

#include "specula/interrupt/interrupt.h"

namespace specula::numeric {

struct Estimate {
  double value = 0;
  double error = 0;  ///< sum of the pieces' |K31 − G15|: an upper bound in practice
};

inline constexpr double kDefaultTolerance = 1e-13;
inline constexpr std::size_t kEvaluationsPerCheck = 256;

template <class F>
Estimate integrate_pieces(const F& f, double a, double b, double width,
                          const std::vector<double>& breakpoints = {},
                          double tolerance = kDefaultTolerance, unsigned max_depth = 15) {
  Estimate total;
  if (!(b > a)) return total;
  width = std::clamp(width, 1e-300, b - a);
  std::vector<double> cuts{0};
  for (double s = 1; a + s * width < b; s *= 4) cuts.push_back(s);
  for (const double x : breakpoints)
    if (x > a && x < b) cuts.push_back((x - a) / width);
  cuts.push_back((b - a) / width);
  std::sort(cuts.begin(), cuts.end());
  std::size_t evaluations = 0;
  auto in_s = [&](double s) {
    if (++evaluations % kEvaluationsPerCheck == 0) check_interrupt();
    return f(a + s * width);
  };
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    if (!(cuts[i + 1] > cuts[i])) continue;
    double error = 0;
    total.value += boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
        in_s, cuts[i], cuts[i + 1], max_depth, tolerance, &error);
    total.error += error;
  }
  total.value *= width;
  total.error *= width;
  return total;
}

}  // namespace specula::numeric
