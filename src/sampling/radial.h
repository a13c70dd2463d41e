#pragma once
// Densities of a direction about an axis that depend on its polar angle alone (sampling/sampler.h):
// the radial part of every lobe and microfacet sampler. Each is a density per solid angle p(x) of
// x = cos(angle from the axis), given with y = −ln x (exact for narrow lobes, where 1 − x
// underflows), and a sampler of the angle from one uniform number by the inverse CDF.
//
// The densities themselves are include/specula/lobes/portable/radial.h's, which the C++ export
// embeds: these classes hold a density's parameters and tables.
#include <functional>
#include <vector>

#include "specula/lobes/portable/radial.h"

namespace specula::sampling {

using radial::PolarAngle;

class PowerRadial {
 public:
  explicit PowerRadial(double n) : n_(n) {}
  double density(double y) const noexcept { return radial::power_density(n_, y); }
  PolarAngle sample(double u) const noexcept { return radial::power_sample(n_, u); }

 private:
  double n_;
};

class BeckmannRadial {
 public:
  explicit BeckmannRadial(double alpha) : alpha_(alpha) {}
  double density(double y) const noexcept { return radial::beckmann_density(alpha_, y); }
  PolarAngle sample(double u) const noexcept { return radial::beckmann_sample(alpha_, u); }

 private:
  double alpha_;
};

/// docs/sampling.md, "The log lobe": with b = ln 2/n and t = y/b ∈ [0, 3], the density in t is
/// F_t(t) e^(−bt)/G(3), F_t = 1 − ½ log₂(1 + t), and G has a closed form through E₁.
class LogRadial {
 public:
  explicit LogRadial(double n) : data_(n) {}
  double density(double y) const noexcept { return radial::log_density(data_, y); }
  PolarAngle sample(double u) const noexcept { return radial::log_sample(data_, u); }
  /// ∫₀^T F_t(s) e^(−bs) ds (exposed for the tests).
  double cdf_integral(double t) const noexcept { return radial::log_t_integral(data_.b, t); }

 private:
  radial::LogRadialData data_;
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
  double density(double y) const noexcept { return radial::table_density(view(), y); }
  PolarAngle sample(double u) const noexcept { return radial::table_sample(view(), u); }
  /// ∫ |p_table − p| dy over [0, y_end], p the normalized density of g (by 8-point Gauss-Legendre
  /// per cell).
  double l1_error() const noexcept { return l1_error_; }
  double width() const noexcept { return width_; }
  double y_end() const noexcept { return y_end_; }
  double ds() const noexcept { return ds_; }
  const std::vector<double>& cumulative() const noexcept { return cumulative_; }

 private:
  radial::TableView view() const noexcept { return {cumulative_.data(), kCells, width_, y_end_, ds_}; }

  double width_, y_end_, ds_;
  std::vector<double> cumulative_;  ///< kCells + 1 values, 0 … 1
  bool usable_ = false;
  double l1_error_ = 0;
};

}  // namespace specula::sampling
