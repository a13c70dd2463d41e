#pragma once
// Densities of a direction about an axis that depend on its polar angle alone (sampling/sampler.h):
// the radial part of every lobe and microfacet sampler. Each is a density per solid angle p(x) of
// x = cos(angle from the axis), given with y = −ln x (exact for narrow lobes, where 1 − x
// underflows), and a sampler of the angle from one uniform number by the inverse CDF.
//
//   Power       (n + 1)/(2π) xⁿ                       x = (1 − u)^(1/(n+1))
//   Beckmann    exp(−tan²/α²)/(π α² x³)  (D·cos)     tan² = −α² ln(1 − u)
//   Log         F_log(x)/(2π ∫₀¹F_log dx)            Newton on the closed-form CDF in t
//   Table       any shape g(y), piecewise constant in y on 4096 cells, sampled by binary search
#include <functional>
#include <vector>

namespace specula::sampling {

struct PolarAngle {
  double cos = 1, sin = 0;
  static PolarAngle from_log_cos(double y) noexcept;
};

class PowerRadial {
 public:
  explicit PowerRadial(double n) : n_(n) {}
  double density(double y) const noexcept;
  PolarAngle sample(double u) const noexcept;

 private:
  double n_;
};

class BeckmannRadial {
 public:
  explicit BeckmannRadial(double alpha) : alpha_(alpha) {}
  double density(double y) const noexcept;
  PolarAngle sample(double u) const noexcept;

 private:
  double alpha_;
};

/// docs/sampling.md, "The log lobe": with b = ln 2/n and t = y/b ∈ [0, 3], the density in t is
/// F_t(t) e^(−bt)/G(3), F_t = 1 − ½ log₂(1 + t), and G has a closed form through E₁.
class LogRadial {
 public:
  explicit LogRadial(double n);
  double density(double y) const noexcept;
  PolarAngle sample(double u) const noexcept;
  /// ∫₀^T F_t(s) e^(−bs) ds (exposed for the tests).
  double cdf_integral(double t) const noexcept;

 private:
  double b_;
  double total_;  ///< G(3)
  std::vector<double> start_;  ///< T at u = j/(size − 1): Newton's first guess
};

class TableRadial {
 public:
  static constexpr int kCells = 4096;
  /// The density ∝ g(y) per solid angle on y ∈ [0, y_end), cells spaced for a lobe of width
  /// `width` > 0 (in y): y = width·(e^s − 1), uniform in s — fine at the peak, ~0.6 % of y in the
  /// tail, whatever the width. g ≥ 0 (negative values count as 0).
  TableRadial(const std::function<double(double)>& g, double width, double y_end);
  /// False if g integrated to 0 (or not finite): nothing to sample.
  bool usable() const noexcept { return usable_; }
  double density(double y) const noexcept;
  PolarAngle sample(double u) const noexcept;
  /// ∫ |p_table − p| dy over [0, y_end], p the normalized density of g (by 8-point Gauss-Legendre
  /// per cell).
  double l1_error() const noexcept { return l1_error_; }
  double width() const noexcept { return width_; }
  double y_end() const noexcept { return y_end_; }
  double ds() const noexcept { return ds_; }
  const std::vector<double>& cumulative() const noexcept { return cumulative_; }

 private:
  double y_at(int cell) const noexcept;
  int cell_of(double y) const noexcept;

  double width_, y_end_, ds_;
  std::vector<double> cumulative_;  ///< kCells + 1 values, 0 … 1
  bool usable_ = false;
  double l1_error_ = 0;
};

}  // namespace specula::sampling
