#pragma once
// Private: golden-section search for a maximum of f on [a, b]. No derivatives and no parabolic
// steps, so it is robust where maxima sit at kinks (clipped lobes, compact supports).
#include <cmath>

namespace specula::numeric {

struct Maximum {
  double at = 0;
  double value = 0;
};

/// Narrows [a, b] until it is shorter than `tolerance`; returns the better of the last two probes.
template <class F>
Maximum golden_section_max(const F& f, double a, double b, double tolerance) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  double c = b - r * (b - a), d = a + r * (b - a);
  double fc = f(c), fd = f(d);
  while (b - a > tolerance) {
    if (fc >= fd) {
      b = d, d = c, fd = fc;
      c = b - r * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + r * (b - a), fd = f(d);
    }
  }
  return fc >= fd ? Maximum{c, fc} : Maximum{d, fd};
}

}  // namespace specula::numeric
