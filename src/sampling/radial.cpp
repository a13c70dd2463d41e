#include "radial.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace specula::sampling {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLn2 = std::numbers::ln2;

// 8-point Gauss-Legendre on [−1, 1]: nodes ±x_i, weights w_i.
constexpr std::array<double, 4> kGaussX{0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
constexpr std::array<double, 4> kGaussW{0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};

template <class F>
void for_gauss_nodes(double a, double b, const F& f) {
  const double mid = (a + b) / 2, half = (b - a) / 2;
  for (std::size_t i = 0; i < kGaussX.size(); ++i) {
    f(mid - half * kGaussX[i], half * kGaussW[i]);
    f(mid + half * kGaussX[i], half * kGaussW[i]);
  }
}

/// e^x E₁(x) for x ≥ 1 by its continued fraction (modified Lentz; Numerical Recipes §6.3).
double scaled_e1(double x) noexcept {
  constexpr double tiny = 1e-300;
  double b = x + 1, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 200; ++i) {
    const double an = -double(i) * i;
    b += 2;
    d = 1 / (an * d + b);
    c = b + an / c;
    const double delta = c * d;
    h *= delta;
    if (std::abs(delta - 1) < 1e-16) break;
  }
  return h;
}

/// ½ log₂(1 + t)'s complement: the log lobe in t-space, 1 − ½ log₂(1 + t) (0 beyond t = 3).
double log_lobe_t(double t) noexcept { return t >= 3 ? 0 : 1 - 0.5 * std::log1p(t) / kLn2; }

}  // namespace

PolarAngle PolarAngle::from_log_cos(double y) noexcept {
  return {std::exp(-y), std::sqrt(std::max(0.0, -std::expm1(-2 * y)))};
}

double PowerRadial::density(double y) const noexcept { return (n_ + 1) / (2 * kPi) * std::exp(-n_ * y); }

PolarAngle PowerRadial::sample(double u) const noexcept {
  return PolarAngle::from_log_cos(-std::log1p(-u) / (n_ + 1));
}

double BeckmannRadial::density(double y) const noexcept {
  const double tan2 = std::expm1(2 * y), a2 = alpha_ * alpha_;
  return std::exp(3 * y - tan2 / a2) / (kPi * a2);
}

PolarAngle BeckmannRadial::sample(double u) const noexcept {
  const double tan2 = -alpha_ * alpha_ * std::log1p(-u);
  const double cos = 1 / std::sqrt(1 + tan2);
  return {cos, std::sqrt(tan2) * cos};
}

LogRadial::LogRadial(double n) : b_(kLn2 / n), total_(0) {
  total_ = cdf_integral(3);
  constexpr int kStarts = 65;
  start_.resize(kStarts);
  for (int j = 0; j < kStarts; ++j) {  // bisection: the sampler's Newton starts from these
    const double target = total_ * j / (kStarts - 1);
    double lo = 0, hi = 3;
    for (int k = 0; k < 60; ++k) {
      const double mid = (lo + hi) / 2;
      (cdf_integral(mid) < target ? lo : hi) = mid;
    }
    start_[j] = j == 0 ? 0 : (j == kStarts - 1 ? 3 : (lo + hi) / 2);
  }
}

// G(T) = (1 − e^(−bT))/b − P(T)/(2 ln 2 · b), P(T) = ∫₀^T e^(−bs)/(1 + s) ds − ln(1 + T) e^(−bT)
// (integration by parts of ln(1 + s) e^(−bs)). For b ≤ 1, P/b by its series in b, whose terms
// need I_k = ∫₀^T s^k/(1 + s) ds = T^k/k − I_(k−1) (no cancellation as b → 0, n → ∞); for b > 1,
// ∫₀^T e^(−bs)/(1 + s) ds = e^b (E₁(b) − E₁(b(1 + T))) through e^x E₁(x) (no overflow).
double LogRadial::cdf_integral(double t) const noexcept {
  if (!(t > 0)) return 0;
  const double b = b_, log_t = std::log1p(t);
  double p_over_b = 0;
  if (b <= 1) {
    double integral = log_t, t_pow = 1, b_pow = 1, factorial = 1;  // I_0, T^0, b^0, 0!
    for (int k = 1; k < 60; ++k) {
      t_pow *= t;
      factorial *= k;
      integral = t_pow / k - integral;
      const double term = (k % 2 ? -1 : 1) * b_pow * (integral - t_pow * log_t) / factorial;
      p_over_b += term;
      if (k > 3 && std::abs(term) < 1e-17 * std::abs(p_over_b)) break;
      b_pow *= b;
    }
  } else {
    const double decay = std::exp(-b * t);
    p_over_b = (scaled_e1(b) - decay * scaled_e1(b * (1 + t)) - log_t * decay) / b;
  }
  return -std::expm1(-b * t) / b - p_over_b / (2 * kLn2);
}

double LogRadial::density(double y) const noexcept {
  const double t = y / b_;
  return t >= 3 ? 0 : log_lobe_t(t) / (2 * kPi * b_ * total_);
}

PolarAngle LogRadial::sample(double u) const noexcept {
  const double target = u * total_;
  const double position = u * double(start_.size() - 1);
  const auto j = std::min(static_cast<std::size_t>(position), start_.size() - 2);
  double lo = start_[j], hi = start_[j + 1];
  double t = lo + (position - double(j)) * (hi - lo);
  for (int k = 0; k < 60; ++k) {  // Newton, kept inside the bracket by bisection
    const double excess = cdf_integral(t) - target;
    (excess < 0 ? lo : hi) = t;
    const double slope = log_lobe_t(t) * std::exp(-b_ * t);
    double next = slope > 0 ? t - excess / slope : (lo + hi) / 2;
    if (!(next > lo && next < hi)) next = (lo + hi) / 2;
    const double step = std::abs(next - t);
    t = next;
    if (step <= 4e-16 * t || hi - lo <= 4e-16 * hi) break;
  }
  return PolarAngle::from_log_cos(b_ * t);
}

TableRadial::TableRadial(const std::function<double(double)>& g, double width, double y_end)
    : width_(width), y_end_(y_end), ds_(std::log1p(y_end / width) / kCells), cumulative_(kCells + 1, 0.0) {
  std::vector<double> mass(kCells);
  auto density_in_y = [&](double y) { return std::max(0.0, g(y)) * std::exp(-y); };
  double total = 0;
  for (int j = 0; j < kCells; ++j) {
    for_gauss_nodes(y_at(j), y_at(j + 1), [&](double y, double w) { mass[j] += w * density_in_y(y); });
    total += mass[j];
  }
  usable_ = total > 0 && std::isfinite(total);
  if (!usable_) return;
  for (int j = 0; j < kCells; ++j) cumulative_[j + 1] = cumulative_[j] + mass[j] / total;
  cumulative_[kCells] = 1;
  for (int j = 0; j < kCells; ++j) {
    const double flat = mass[j] / total / (y_at(j + 1) - y_at(j));
    for_gauss_nodes(y_at(j), y_at(j + 1),
                    [&](double y, double w) { l1_error_ += w * std::abs(density_in_y(y) / total - flat); });
  }
}

double TableRadial::y_at(int cell) const noexcept {
  return cell >= kCells ? y_end_ : width_ * std::expm1(ds_ * cell);
}

int TableRadial::cell_of(double y) const noexcept {
  return std::clamp(static_cast<int>(std::log1p(y / width_) / ds_), 0, kCells - 1);
}

double TableRadial::density(double y) const noexcept {
  if (!(y >= 0 && y < y_end_)) return 0;
  const int j = cell_of(y);
  const double per_y = (cumulative_[j + 1] - cumulative_[j]) / (y_at(j + 1) - y_at(j));
  return per_y * std::exp(y) / (2 * kPi);
}

PolarAngle TableRadial::sample(double u) const noexcept {
  const auto above = std::upper_bound(cumulative_.begin(), cumulative_.end(), u);
  const int j = std::clamp(static_cast<int>(above - cumulative_.begin()) - 1, 0, kCells - 1);
  const double mass = cumulative_[j + 1] - cumulative_[j];
  const double fraction = mass > 0 ? std::clamp((u - cumulative_[j]) / mass, 0.0, 1.0) : 0.5;
  return PolarAngle::from_log_cos(y_at(j) + fraction * (y_at(j + 1) - y_at(j)));
}

}  // namespace specula::sampling
