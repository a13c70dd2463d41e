#include "verify.h"

#include <cmath>
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

AtParam error_at(const std::function<Model(double)>& lobe_at, const Settings& s, double p) {
  const lobes::Lobe lobe = lobe_at(p).lobe();
  return {p, analysis::approximation_error(lobe, target_at(s, p).lobe(), s.zone), non_finite_point(lobe)};
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
