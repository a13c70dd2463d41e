// The radial densities of importance sampling (docs/sampling.md): a lobe's shape about its axis as
// a density per solid angle of x = cos(angle), given with y = −ln x (exact for narrow lobes, where
// 1 − x underflows), and its inverse CDF from one uniform number. Needs <cmath> alone: the sampling
// module (src/sampling/radial.cpp) and the log lobe's closed-form k (src/lobes/closed_form.cpp)
// compile this file, and `specula export --format cpp` embeds its text in every exported header,
// so that the exported sampler and specula's are one source.
//
//   Power       (n + 1)/(2π) xⁿ                       x = (1 − u)^(1/(n+1))
//   Beckmann    exp(−tan²/α²)/(π α² x³)  (D·cos)     tan² = −α² ln(1 − u)
//   Log         F_log(x)/(2π ∫₀¹F_log dx)            Newton on the closed-form CDF in t
//   Table       piecewise constant in y on cells y_j = width (e^(j ds) − 1), by binary search
#ifndef SPECULA_LOBES_PORTABLE_RADIAL_H
#define SPECULA_LOBES_PORTABLE_RADIAL_H
#include <cmath>

namespace specula::radial {

inline constexpr double kPi = 3.141592653589793;
inline constexpr double kLn2 = 0.6931471805599453;

struct PolarAngle {
  double cos = 1, sin = 0;
};

inline PolarAngle from_log_cos(double y) {
  const double sin2 = -std::expm1(-2 * y);
  return {std::exp(-y), std::sqrt(sin2 > 0 ? sin2 : 0.0)};
}

// Power-cosine.
inline double power_density(double n, double y) { return (n + 1) / (2 * kPi) * std::exp(-n * y); }
inline PolarAngle power_sample(double n, double u) { return from_log_cos(-std::log1p(-u) / (n + 1)); }

// Beckmann's D cos θ_h.
inline double beckmann_density(double alpha, double y) {
  const double tan2 = std::expm1(2 * y), a2 = alpha * alpha;
  return std::exp(3 * y - tan2 / a2) / (kPi * a2);
}
inline PolarAngle beckmann_sample(double alpha, double u) {
  const double tan2 = -alpha * alpha * std::log1p(-u);
  const double cos = 1 / std::sqrt(1 + tan2);
  return {cos, std::sqrt(tan2) * cos};
}

/// e^x E₁(x) for x ≥ 1 by its continued fraction 1/(x + 1 − 1²/(x + 3 − 2²/(x + 5 − …))),
/// evaluated from its tail at a depth that makes the truncation negligible (12 + 100/√x terms):
/// each step rounds once, so the error does not grow with the depth as a forward evaluation's does.
/// Max error: 4 ulp relative for x ∈ [1, 700] (tests/lobes against Boost's E₁ in long double).
inline double scaled_e1(double x) {
  const int depth = 12 + static_cast<int>(100 / std::sqrt(x));
  double tail = 0;
  for (int i = depth; i >= 1; --i) tail = -double(i) * i / (x + 2 * i + 1 + tail);
  return 1 / (x + 1 + tail);
}

/// The log lobe in t = −n log₂ c: F_t(t) = 1 − ½ log₂(1 + t) on [0, 3], 0 beyond.
inline double log_lobe_t(double t) { return t >= 3 ? 0 : 1 - 0.5 * std::log1p(t) / kLn2; }

/// G_b(T) = ∫₀^T F_t(s) e^(−bs) ds = (1 − e^(−bT))/b − P(T)/(2 ln 2 · b), where
/// P(T) = ∫₀^T e^(−bs)/(1 + s) ds − ln(1 + T) e^(−bT) (integration by parts of ln(1 + s) e^(−bs)).
/// For b ≤ 1, P/b by its series in b, whose terms need I_k = ∫₀^T s^k/(1 + s) ds = T^k/k − I_(k−1)
/// (no cancellation as b → 0); for b > 1, ∫₀^T e^(−bs)/(1 + s) ds = e^b (E₁(b) − E₁(b(1 + T)))
/// through e^x E₁(x) (no overflow). Max error: 1e-14 of G_b(3) for T ∈ [0, 3], b ∈ [1e-9, 1e3]
/// (relative to G_b(T) itself only away from T = 0, where the E₁ difference cancels).
inline double log_t_integral(double b, double t) {
  if (!(t > 0)) return 0;
  const double log_t = std::log1p(t);
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

/// The log lobe's density in t = y/b, b = ln 2/n: F_t(t) e^(−bt)/G_b(3), and Newton's first
/// guesses for its inverse, T at u = j/64 by bisection.
struct LogRadialData {
  static constexpr int kStarts = 65;
  double b = 0;
  double total = 0;  ///< G_b(3)
  double start[kStarts] = {};

  explicit LogRadialData(double n) : b(kLn2 / n), total(log_t_integral(b, 3)) {
    for (int j = 0; j < kStarts; ++j) {
      const double target = total * j / (kStarts - 1);
      double lo = 0, hi = 3;
      for (int k = 0; k < 60; ++k) {
        const double mid = (lo + hi) / 2;
        (log_t_integral(b, mid) < target ? lo : hi) = mid;
      }
      start[j] = j == 0 ? 0 : (j == kStarts - 1 ? 3 : (lo + hi) / 2);
    }
  }
};

inline double log_density(const LogRadialData& log, double y) {
  const double t = y / log.b;
  return t >= 3 ? 0 : log_lobe_t(t) / (2 * kPi * log.b * log.total);
}

inline PolarAngle log_sample(const LogRadialData& log, double u) {
  const double target = u * log.total;
  const double position = u * (LogRadialData::kStarts - 1);
  const int last = LogRadialData::kStarts - 2;
  const int j = position >= last ? last : static_cast<int>(position);
  double lo = log.start[j], hi = log.start[j + 1];
  double t = lo + (position - double(j)) * (hi - lo);
  for (int k = 0; k < 60; ++k) {  // Newton, kept inside the bracket by bisection
    const double excess = log_t_integral(log.b, t) - target;
    (excess < 0 ? lo : hi) = t;
    const double slope = log_lobe_t(t) * std::exp(-log.b * t);
    double next = slope > 0 ? t - excess / slope : (lo + hi) / 2;
    if (!(next > lo && next < hi)) next = (lo + hi) / 2;
    const double step = std::abs(next - t);
    t = next;
    if (step <= 4e-16 * t || hi - lo <= 4e-16 * hi) break;
  }
  return from_log_cos(log.b * t);
}

/// A tabulated inverse CDF in y: cells with edges y_j = width (e^(j ds) − 1) (y_cells = y_end),
/// cumulative[j] = P(y < y_j), cells + 1 values from 0 to 1.
struct TableView {
  const double* cumulative = nullptr;
  int cells = 0;
  double width = 1, y_end = 0, ds = 1;

  double y_at(int cell) const { return cell >= cells ? y_end : width * std::expm1(ds * cell); }
  int cell_of(double y) const {
    const int cell = static_cast<int>(std::log1p(y / width) / ds);
    return cell < 0 ? 0 : (cell > cells - 1 ? cells - 1 : cell);
  }
};

inline double table_density(const TableView& table, double y) {
  if (!(y >= 0 && y < table.y_end)) return 0;
  const int j = table.cell_of(y);
  const double per_y = (table.cumulative[j + 1] - table.cumulative[j]) / (table.y_at(j + 1) - table.y_at(j));
  return per_y * std::exp(y) / (2 * kPi);
}

inline PolarAngle table_sample(const TableView& table, double u) {
  int above = 0;  // the first edge whose probability exceeds u (std::upper_bound)
  for (int count = table.cells + 1; count > 0;) {
    const int half = count / 2;
    if (!(u < table.cumulative[above + half])) above += half + 1, count -= half + 1;
    else count = half;
  }
  const int j = above - 1 < 0 ? 0 : (above - 1 > table.cells - 1 ? table.cells - 1 : above - 1);
  const double mass = table.cumulative[j + 1] - table.cumulative[j];
  double fraction = 0.5;
  if (mass > 0) {
    fraction = (u - table.cumulative[j]) / mass;
    fraction = fraction < 0 ? 0 : (fraction > 1 ? 1 : fraction);
  }
  return from_log_cos(table.y_at(j) + fraction * (table.y_at(j + 1) - table.y_at(j)));
}

}  // namespace specula::radial
#endif  // SPECULA_LOBES_PORTABLE_RADIAL_H
