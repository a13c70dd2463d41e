#pragma once
// Cosines that probe every region of a lobe (tests/simd): dense and random in c, dense in
// t = −n log₂ c (the log lobe's variable) and near its cut-off t = 3, dense in the angle (Gauss),
// powers of two down to the subnormals, and the edge cases.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

namespace specula::simd {

/// Cosines that probe every region of the lobe at exponent n.
template <class T>
std::vector<T> probe_cosines(double n, std::size_t dense) {
  std::vector<T> c;
  std::mt19937_64 rng(20231105u);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t i = 0; i <= dense; ++i) c.push_back(T(double(i) / double(dense)));
  for (std::size_t i = 0; i < dense; ++i) c.push_back(T(uniform(rng)));
  for (std::size_t i = 0; i <= 2 * dense; ++i) c.push_back(T(std::exp2(-4.0 * double(i) / double(2 * dense) / n)));
  for (std::size_t i = 0; i < dense; ++i) {  // t close to 0 and to the log lobe's cut-off t = 3
    const double t = 3 * std::exp(-30 * uniform(rng));
    c.push_back(T(std::exp2(-t / n)));
    c.push_back(T(std::exp2(-(3 - t * 1e-3) / n)));
  }
  const double theta_max = std::min(std::sqrt(60.0 / n), std::numbers::pi / 2);  // Gauss down to e^(-30)
  for (std::size_t i = 0; i <= dense; ++i) c.push_back(T(std::cos(theta_max * double(i) / double(dense))));
  for (int k = std::numeric_limits<T>::min_exponent - std::numeric_limits<T>::digits; k < 0; ++k)
    c.push_back(T(std::ldexp(1.0, k)));
  const T c0 = T(std::exp2(-3 / double(T(n))));  // the log lobe's cut-off, and its neighbours
  for (const T v : {c0, std::nextafter(c0, T(0)), std::nextafter(c0, T(1)), T(std::sqrt(0.5)),
                    std::nextafter(T(1), T(0)), T(0), T(-0.0), T(1), T(-1), T(2), T(-0.5),
                    std::numeric_limits<T>::denorm_min(), std::numeric_limits<T>::min(),
                    std::numeric_limits<T>::infinity(), -std::numeric_limits<T>::infinity()})
    c.push_back(v);
  return c;
}

}  // namespace specula::simd
