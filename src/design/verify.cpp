#include "verify.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>
#include <optional>

#include "fitting.h"
#include <memory>
#include <span>
#include <tuple>
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

// The largest of `error` on [a, b] by golden-section search, from the best point known.
template <class Error>
std::pair<double, double> golden_max(Error error, double a, double b, double best_x, double best) {
  constexpr double kGolden = 0.6180339887498949;
  double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a), e1 = error(x1), e2 = error(x2);
  for (int step = 0; step < 60; ++step) {
    if (e1 >= e2) {
      b = x2, x2 = x1, e2 = e1, x1 = b - kGolden * (b - a), e1 = error(x1);
    } else {
      a = x1, x1 = x2, e1 = e2, x2 = a + kGolden * (b - a), e2 = error(x2);
    }
  }
  for (const auto& [x, e] : {std::pair{x1, e1}, std::pair{x2, e2}})
    if (e > best) best_x = x, best = e;
  return {best_x, best};
}

// One variable's points over (0, 1] for a function target's error: even, then in t² toward grazing
// (a cosine → 0), then powers of ten down to 1e-300 (the limit there). 1024 + 255 + 98 points for
// one variable, 64 + 15 + 10 a side for two, 20 + 4 + 4 for three.
std::vector<double> error_axis(std::size_t variables) {
  const int even = variables == 1 ? 1024 : variables == 2 ? 64 : 20;
  std::vector<double> out;
  for (int i = 1; i <= even; ++i) out.push_back(static_cast<double>(i) / even);
  for (int i = 1; i < even / 4; ++i) out.push_back(std::pow(static_cast<double>(i) / (even / 4), 2) / 64);
  for (int e = -300; e <= -9; e += variables == 1 ? 3 : variables == 2 ? 32 : 80) out.push_back(std::pow(10.0, e));
  std::ranges::sort(out);
  return out;
}

// |F − T| of a function target at parameter p over the box (0, 1]^k of its per-pixel variables: the
// tensor grid of error_axis, then golden-section refinement around its 8 largest local maxima, one
// variable at a time within a grid step (two rounds), and along each edge of the box from the
// edge's 2 largest local maxima — exact where the error is unimodal near one. max_rel where T ≥ zone × T's largest value on the grid. argmax_abs_deg: acos of the first variable.
struct FunctionError {
  analysis::ApproximationError error;
  std::optional<double> not_finite_u;
};

FunctionError function_error(const expr::Expression& f, const std::function<double(std::span<const double>)>& t,
                             const Settings& s, double p) {
  const std::size_t k = s.variables.size();
  // Each variable's points: error_axis for those over (0, 1], the output index's own values.
  const std::size_t continuous = k - (output_count(s.target) > 1 ? 1 : 0);
  std::vector<std::vector<double>> axes(k, error_axis(continuous));
  for (std::size_t v = 0; v < k; ++v)
    if (is_output_variable(s, v)) axes[v] = output_axis(s);
  std::vector<std::size_t> stride(k, 1);
  for (std::size_t v = 1; v < k; ++v) stride[v] = stride[v - 1] * axes[v - 1].size();
  const std::size_t rows = stride.back() * axes.back().size();
  std::vector<std::vector<double>> columns(k);
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t v = 0; v < k; ++v) columns[v].push_back(axes[v][r / stride[v] % axes[v].size()]);
  if (!s.param.empty()) columns.emplace_back(rows, p);
  const std::vector<double> fv = evaluate_rows(f, columns), tv = target_values(s, columns);
  FunctionError out;
  for (std::size_t r = 0; r < rows; ++r)
    if (!std::isfinite(fv[r])) {
      out.not_finite_u = -std::log(columns[0][r]);
      return out;
    }
  const double top = *std::ranges::max_element(tv);
  std::vector<double> point(columns.size());
  const auto at = [&](std::span<const double> x) {
    std::ranges::copy(x, point.begin());
    if (!s.param.empty()) point.back() = p;
    return std::pair{expr::evaluate(f, point), t(point)};
  };
  const auto abs_error = [&](std::span<const double> x) { const auto [a, b] = at(x); return std::abs(a - b); };
  const auto rel_error = [&](std::span<const double> x) {
    const auto [a, b] = at(x);
    return b >= s.zone * top && b > 0 ? std::abs(a - b) / b : 0.0;
  };
  const auto index = [&](std::size_t r, std::size_t v) { return r / stride[v] % axes[v].size(); };
  // Refines from each of the grid's 8 largest local maxima (a cusp — a clamp's kink — may peak
  // between grid points below another point's value), one variable at a time within a grid step,
  // twice; the output index is not refined (it has no values between its own).
  const auto worst = [&](auto error, const std::vector<double>& errors) {
    // The grid's local maxima (each at least its neighbours along every variable over (0, 1]), largest first.
    std::vector<std::size_t> order;
    for (std::size_t r = 0; r < rows; ++r) {
      bool peak = true;
      for (std::size_t v = 0; v < k && peak; ++v) {
        if (is_output_variable(s, v)) continue;
        const std::size_t i = index(r, v);
        if (i > 0 && errors[r - stride[v]] > errors[r]) peak = false;
        if (i + 1 < axes[v].size() && errors[r + stride[v]] > errors[r]) peak = false;
      }
      if (peak) order.push_back(r);
    }
    std::ranges::sort(order, [&](std::size_t a, std::size_t b) { return errors[a] > errors[b]; });
    // A plateau (the limit at grazing, printed the same at every tiny cosine) counts once.
    const auto distinct = std::ranges::unique(order, [&](std::size_t a, std::size_t b) { return errors[a] == errors[b]; });
    order.erase(distinct.begin(), distinct.end());
    const std::size_t starts = std::min<std::size_t>(8, order.size());
    std::pair<std::vector<double>, double> best{std::vector<double>(k), -1};
    for (std::size_t start = 0; start < starts; ++start) {
      std::vector<double> x(k);
      for (std::size_t v = 0; v < k; ++v) x[v] = columns[v][order[start]];
      double found = errors[order[start]];
      for (int round = 0; round < 2; ++round)
        for (std::size_t v = 0; v < k; ++v) {
          if (is_output_variable(s, v)) continue;
          const std::vector<double>& axis = axes[v];
          const auto it = std::ranges::lower_bound(axis, x[v]);
          const double a = it == axis.begin() ? axis.front() : *(it - 1), b = it + 1 >= axis.end() ? axis.back() : *(it + 1);
          if (!(a < b)) continue;
          std::vector<double> y = x;
          const auto along = [&](double value) { y[v] = value; return error(y); };
          std::tie(x[v], found) = golden_max(along, a, b, x[v], found);
        }
      if (found > best.second) best = {x, found};
    }
    // Each edge of the box (every variable but one at an end of its axis; the output index at
    // each of its values) as a problem of one variable: its 2 largest local maxima refined along
    // it. A ridge across the variables climbs to the box's side, where no start in the interior
    // reaches (a kink along NoV·NoL = const).
    for (std::size_t w = 0; w < k && continuous > 1; ++w) {
      if (is_output_variable(s, w)) continue;
      const std::size_t n = axes[w].size();
      for (std::size_t r0 = 0; r0 < rows; ++r0) {
        // r0: the edge's first row (w at 0), every other variable at an end (or any output).
        bool corner = index(r0, w) == 0;
        for (std::size_t v = 0; v < k && corner; ++v)
          if (v != w && !is_output_variable(s, v)) corner = index(r0, v) == 0 || index(r0, v) + 1 == axes[v].size();
        if (!corner) continue;
        std::vector<std::size_t> line;  // the rows of this edge, in the order of variable w
        for (std::size_t i = 0; i < n; ++i) line.push_back(r0 + i * stride[w]);
        std::vector<std::size_t> peaks;
        for (std::size_t i = 0; i < n; ++i)
          if ((i == 0 || errors[line[i - 1]] <= errors[line[i]]) && (i + 1 == n || errors[line[i + 1]] <= errors[line[i]]))
            peaks.push_back(i);
        std::ranges::sort(peaks, [&](std::size_t a, std::size_t b) { return errors[line[a]] > errors[line[b]]; });
        for (std::size_t j = 0; j < std::min<std::size_t>(2, peaks.size()); ++j) {
          const std::size_t i = peaks[j];
          std::vector<double> x(k);
          for (std::size_t v = 0; v < k; ++v) x[v] = columns[v][line[i]];
          const double a = axes[w][i == 0 ? 0 : i - 1], b = axes[w][std::min(i + 1, n - 1)];
          std::vector<double> y = x;
          const auto along = [&](double value) { y[w] = value; return error(y); };
          double found = errors[line[i]];
          if (a < b) std::tie(x[w], found) = golden_max(along, a, b, x[w], found);
          if (found > best.second) best = {x, found};
        }
      }
    }
    return best;
  };
  std::vector<double> abs_errors(rows), rel_errors(rows);
  for (std::size_t r = 0; r < rows; ++r) {
    abs_errors[r] = std::abs(fv[r] - tv[r]);
    rel_errors[r] = tv[r] >= s.zone * top && tv[r] > 0 ? abs_errors[r] / tv[r] : 0.0;
  }
  const auto [abs_x, abs_max] = worst(abs_error, abs_errors);
  out.error.max_abs = abs_max;
  out.error.argmax_abs_deg = std::acos(std::min(1.0, abs_x[0])) * 180 / std::numbers::pi;
  out.error.max_rel_epicenter = worst(rel_error, rel_errors).second;
  return out;
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
AtParam refine(const std::function<AtParam(double)>& error_at, const Settings& s, double a, double b,
               AtParam best, Value value, const std::function<bool()>& stop) {
  const bool log = log_spaced(s.lo, s.hi);
  const auto to_p = [&](double t) { return log ? std::exp(t) : t; };
  double lo = log ? std::log(a) : a, hi = log ? std::log(b) : b;
  constexpr double kGolden = 0.6180339887498949;
  AtParam x1 = error_at(to_p(hi - kGolden * (hi - lo)));
  AtParam x2 = error_at(to_p(lo + kGolden * (hi - lo)));
  for (int step = 0; step < kRefineSteps && !stop(); ++step) {
    if (value(x1) > value(best)) best = x1;
    if (value(x2) > value(best)) best = x2;
    if (value(x1) >= value(x2)) {
      hi = log ? std::log(x2.param) : x2.param;
      x2 = x1;
      x1 = error_at(to_p(hi - kGolden * (hi - lo)));
    } else {
      lo = log ? std::log(x1.param) : x1.param;
      x1 = x2;
      x2 = error_at(to_p(lo + kGolden * (hi - lo)));
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

// The error at one parameter value: a lobe's by `specula error`'s maxima, a function's over its box.
std::function<AtParam(double)> error_at_param(const Lobe& l, const Settings& s) {
  if (is_function_target(s.target)) {
    auto f = std::make_shared<const expr::Expression>(function_expression(s, l.formula));
    auto t = std::make_shared<const std::function<double(std::span<const double>)>>(target_function(s));
    return [f, t, &s](double p) {
      const FunctionError e = function_error(*f, *t, s, p);
      return AtParam{p, e.error, e.not_finite_u};
    };
  }
  return [lobe_at = design::lobe_at(l, s), &s](double p) { return error_at(lobe_at, s, p); };
}

DomainError domain_error(const Lobe& l, const Settings& s, const std::function<bool()>& stop) {
  const std::function<AtParam(double)> error_at = error_at_param(l, s);
  const std::vector<double> grid = param_grid(s.lo, s.hi, kVerifyGrid);
  std::vector<AtParam> at;
  for (double p : grid) {
    if (stop()) break;
    at.push_back(error_at(p));
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
    return a < b ? refine(error_at, s, a, b, at[best], value, stop) : at[best];
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
