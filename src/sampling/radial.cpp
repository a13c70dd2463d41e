#include "radial.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace specula::sampling {
namespace {

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

}  // namespace

TableRadial::TableRadial(const std::function<double(double)>& g, double width, double y_end)
    : width_(width), y_end_(y_end), ds_(std::log1p(y_end / width) / kCells), cumulative_(kCells + 1, 0.0) {
  const radial::TableView cells = view();
  std::vector<double> mass(kCells);
  auto density_in_y = [&](double y) { return std::max(0.0, g(y)) * std::exp(-y); };
  double total = 0;
  for (int j = 0; j < kCells; ++j) {
    for_gauss_nodes(cells.y_at(j), cells.y_at(j + 1), [&](double y, double w) { mass[j] += w * density_in_y(y); });
    total += mass[j];
  }
  usable_ = total > 0 && std::isfinite(total);
  if (!usable_) return;
  for (int j = 0; j < kCells; ++j) cumulative_[j + 1] = cumulative_[j] + mass[j] / total;
  cumulative_[kCells] = 1;
  for (int j = 0; j < kCells; ++j) {
    const double flat = mass[j] / total / (cells.y_at(j + 1) - cells.y_at(j));
    for_gauss_nodes(cells.y_at(j), cells.y_at(j + 1),
                    [&](double y, double w) { l1_error_ += w * std::abs(density_in_y(y) / total - flat); });
  }
}

}  // namespace specula::sampling
