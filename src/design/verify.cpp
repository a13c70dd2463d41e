#include "verify.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>
#include <optional>

#include "fitting.h"
#include "specula/analysis/error.h"
#include "specula/catalogue/catalogue.h"
#include "specula/interrupt/interrupt.h"

namespace specula::design {

namespace {

constexpr int kRefineSteps = 40;
constexpr int kProbeEven = 256, kProbeNear = 64;     // points of the probe: even in c, and in u near the peak
constexpr double kProbeNearEnd = 40;                 // … up to this u (the error's own end)
constexpr double kSmallestLogCos = 745;              // c = 5e-324: the fits' last row

struct AtParam {
  double param;
  analysis::ApproximationError error;
  std::optional<double> not_finite_u;  // a point of the probe where the lobe is not finite
};

std::optional<double> non_finite_point(const lobes::Lobe& lobe) {
  for (double u : probe_log_cos())
    if (!std::isfinite(lobes::at_log_cos(lobe, u))) return u;
  return std::nullopt;
}

// The largest of `error` on [a, b] by golden-section search from the bracket's middle.
template <class Error>
std::pair<double, double> golden_max(Error error, double a, double b, double best_c, double best) {
  constexpr double kGolden = 0.6180339887498949;
  double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a), e1 = error(x1), e2 = error(x2);
  for (int step = 0; step < 60; ++step) {
    if (e1 >= e2) {
      b = x2, x2 = x1, e2 = e1, x1 = b - kGolden * (b - a), e1 = error(x1);
    } else {
      a = x1, x1 = x2, e1 = e2, x2 = a + kGolden * (b - a), e2 = error(x2);
    }
  }
  for (const auto& [c, e] : {std::pair{x1, e1}, std::pair{x2, e2}})
    if (e > best) best_c = c, best = e;
  return {best_c, best};
}

// |F − T| of a function target over c ∈ (0, 1], not in u around a peak: 1024 points even in c,
// 256 in c² toward grazing and powers of ten down to 1e-300, then golden-section refinement of the worst point's bracket (exact
// where the error is unimodal within one bracket). max_rel where T ≥ zone × T's largest value.
analysis::ApproximationError function_error(const lobes::Lobe& f, const lobes::Lobe& t, double zone) {
  std::vector<double> c;
  for (int i = 1; i <= 1024; ++i) c.push_back(i / 1024.0);
  for (int i = 1; i < 256; ++i) c.push_back(std::pow(i / 256.0, 2) / 64);
  for (int e = -300; e <= -9; e += 3) c.push_back(std::pow(10.0, e));  // the limit at grazing, c → 0⁺
  std::ranges::sort(c);
  std::vector<double> target(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) target[i] = lobes::eval(t, c[i]);
  const double top = *std::ranges::max_element(target);
  const auto abs_error = [&](double x) { return std::abs(lobes::eval(f, x) - lobes::eval(t, x)); };
  const auto rel_error = [&](double x) {
    const double v = lobes::eval(t, x);
    return v >= zone * top && v > 0 ? std::abs(lobes::eval(f, x) - v) / v : 0.0;
  };
  const auto worst = [&](auto error) {
    std::size_t at = 0;
    double best = -1;
    for (std::size_t i = 0; i < c.size(); ++i)
      if (const double e = error(c[i]); e > best || std::isnan(e)) at = i, best = std::isnan(e) ? INFINITY : e;
    if (!std::isfinite(best)) return std::pair{c[at], best};
    return golden_max(error, c[at == 0 ? 0 : at - 1], c[std::min(at + 1, c.size() - 1)], c[at], best);
  };
  const auto [abs_c, abs_max] = worst(abs_error);
  analysis::ApproximationError out;
  out.max_abs = abs_max;
  out.argmax_abs_deg = std::acos(std::min(1.0, abs_c)) * 180 / std::numbers::pi;
  out.max_rel_epicenter = worst(rel_error).second;
  return out;
}

AtParam error_at(const std::function<Model(double)>& lobe_at, const Settings& s, double p) {
  const lobes::Lobe lobe = lobe_at(p).lobe(), target = target_at(s, p).lobe();
  if (is_function_target(s.target)) return {p, function_error(lobe, target, s.zone), non_finite_point(lobe)};
  return {p, analysis::approximation_error(lobe, target, s.zone), non_finite_point(lobe)};
}

DomainError not_finite_at(const AtParam& x) {
  return {INFINITY, std::exp(-*x.not_finite_u), x.param, INFINITY, x.param, false};
}

// Golden-section search for the largest `value` on [a, b] in t = log p (or p), from the best
// of the grid.
template <class Value>
AtParam refine(const std::function<Model(double)>& lobe_at, const Settings& s, double a, double b,
               AtParam best, Value value, const std::function<bool()>& stop) {
  const bool log = log_spaced(s.lo, s.hi);
  const auto to_p = [&](double t) { return log ? std::exp(t) : t; };
  double lo = log ? std::log(a) : a, hi = log ? std::log(b) : b;
  constexpr double kGolden = 0.6180339887498949;
  AtParam x1 = error_at(lobe_at, s, to_p(hi - kGolden * (hi - lo)));
  AtParam x2 = error_at(lobe_at, s, to_p(lo + kGolden * (hi - lo)));
  for (int step = 0; step < kRefineSteps && !stop(); ++step) {
    if (value(x1) > value(best)) best = x1;
    if (value(x2) > value(best)) best = x2;
    if (value(x1) >= value(x2)) {
      hi = log ? std::log(x2.param) : x2.param;
      x2 = x1;
      x1 = error_at(lobe_at, s, to_p(hi - kGolden * (hi - lo)));
    } else {
      lo = log ? std::log(x1.param) : x1.param;
      x1 = x2;
      x2 = error_at(lobe_at, s, to_p(lo + kGolden * (hi - lo)));
    }
  }
  if (value(x1) > value(best)) best = x1;
  if (value(x2) > value(best)) best = x2;
  return best;
}

}  // namespace

const std::vector<double>& probe_log_cos() {
  static const std::vector<double> points = [] {
    std::vector<double> u;
    for (int i = 1; i <= kProbeEven; ++i) u.push_back(-std::log(static_cast<double>(i) / kProbeEven));
    for (int j = 0; j <= kProbeNear; ++j) {
      const double t = static_cast<double>(j) / kProbeNear;
      u.push_back(kProbeNearEnd * t * t);
    }
    u.push_back(kSmallestLogCos);
    return u;
  }();
  return points;
}

DomainError domain_error(const Lobe& l, const Settings& s, const std::function<bool()>& stop) {
  const std::function<Model(double)> lobe_at = design::lobe_at(l, s);
  const std::vector<double> grid = param_grid(s.lo, s.hi, kVerifyGrid);
  std::vector<AtParam> at;
  for (double p : grid) {
    if (stop()) break;
    at.push_back(error_at(lobe_at, s, p));
  }
  DomainError out;
  if (at.empty()) return out;
  for (const AtParam& x : at)
    if (x.not_finite_u) return not_finite_at(x);
  const auto abs_of = [](const AtParam& x) { return x.not_finite_u ? INFINITY : x.error.max_abs; };
  const auto rel_of = [](const AtParam& x) { return x.not_finite_u ? INFINITY : x.error.max_rel_epicenter; };
  const auto worst = [&](auto value) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < at.size(); ++i)
      if (value(at[i]) > value(at[best])) best = i;
    const double a = grid[best == 0 ? 0 : best - 1], b = grid[std::min(best + 1, at.size() - 1)];
    return a < b ? refine(lobe_at, s, a, b, at[best], value, stop) : at[best];
  };
  const AtParam abs = worst(abs_of), rel = worst(rel_of);
  for (const AtParam& x : {abs, rel})
    if (x.not_finite_u) return not_finite_at(x);
  out.max_abs = abs.error.max_abs;
  out.argmax_c = std::cos(abs.error.argmax_abs_deg * std::numbers::pi / 180);
  out.argmax_param = abs.param;
  out.max_rel = rel.error.max_rel_epicenter;
  out.argmax_rel_param = rel.param;
  return out;
}

}  // namespace specula::design
