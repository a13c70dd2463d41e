#include "fitting.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <functional>
#include <random>

#include "specula/catalogue/catalogue.h"
#include "specula/fit/fit.h"

namespace specula::design {

using expr::Node;
using expr::Op;

namespace {

constexpr int kRandomStarts = 4;  // at the first grid value, besides the identity
constexpr std::size_t kWidthRows = 64, kUniformRows = 33;
constexpr double kWidths = 12;  // rows in u reach 12 half-maximum widths (cⁿ is 2.4e-4 there)

// u where the target falls to half its peak; inf where it never does on (0, 745].
double half_max_u(const lobes::Lobe& target) {
  const double peak = lobes::at_log_cos(target, 0);
  double hi = 1e-12;
  while (lobes::at_log_cos(target, hi) > peak / 2) {
    hi *= 2;
    if (hi > 745) return INFINITY;
  }
  double lo = 0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = (lo + hi) / 2;
    (lobes::at_log_cos(target, mid) > peak / 2 ? lo : hi) = mid;
  }
  return hi;
}

fit::Metric metric_of(const Settings& s) {
  return s.objective == Objective::max_rel ? fit::Metric::max_rel : fit::Metric::max_abs;
}

// The shape's expression with the first `fixed` constants turned into variables k0, k1, … after
// the per-pixel variables.
expr::Expression with_fixed(const Shape& shape, std::size_t fixed, std::span<const double> free_values,
                            const std::vector<std::string>& names) {
  std::vector<Node> nodes = shape.nodes;
  std::vector<std::string> variables = names;
  for (std::size_t k = 0; k < fixed; ++k) variables.push_back(fmt::format("k{}", k));
  std::size_t index = 0, free_index = 0;
  for (auto& n : nodes)
    if (n.op == Op::constant && !expr::is_exact(n)) {
      if (index < fixed) n = {Op::variable, static_cast<std::uint32_t>(index + names.size()), 0};
      else n.value = free_values[free_index++];
      ++index;
    }
  return expr::Expression(std::move(nodes), std::move(variables));
}

std::vector<double> free_values(const expr::Expression& e) {
  std::vector<double> out;
  for (const auto& n : e.nodes())
    if (n.op == Op::constant && !expr::is_exact(n)) out.push_back(n.value);
  return out;
}

struct Fitted {
  std::vector<double> constants;  // every constant, fixed ones included
  double error = INFINITY;
};

double lobe_error(const expr::Expression& e, const fit::Data& data, const Settings& s, std::span<const double> target) {
  std::vector<std::span<const double>> columns;
  for (const auto& c : data.columns) columns.emplace_back(c);
  std::vector<double> values(target.size());
  expr::evaluate_batch(e, columns, values);
  const bool lobe = !is_function_target(s.target);  // a lobe is never negative; a function may dip below 0 as an error
  double worst = 0;
  for (std::size_t r = 0; r < values.size(); ++r) {
    if (!std::isfinite(values[r]) || (lobe && values[r] < 0)) return INFINITY;
    const double d = std::abs(values[r] - target[r]);
    worst = std::max(worst, s.objective == Objective::max_rel ? d / target[r] : d);
  }
  return worst;
}

fit::Data data_for(const Samples& rows, std::span<const double> fixed, const std::vector<std::string>& names) {
  fit::Data data;
  data.variables = names;
  data.columns = rows.x;
  for (std::size_t k = 0; k < fixed.size(); ++k) {
    data.variables.push_back(fmt::format("k{}", k));
    data.columns.emplace_back(rows.value.size(), fixed[k]);
  }
  data.target = rows.value;
  return data;
}

Fitted fit_once(const Shape& shape, const Samples& rows, const Settings& s, std::span<const double> fixed,
                std::span<const double> start) {
  const fit::Data data = data_for(rows, fixed, s.variables);
  expr::Expression e = with_fixed(shape, fixed.size(), start, s.variables);
  if (shape.constants > static_cast<int>(fixed.size())) e = fit::fit_formula_constants(e, data, metric_of(s)).formula;
  Fitted out;
  out.constants.assign(fixed.begin(), fixed.end());
  for (double v : free_values(e)) out.constants.push_back(v);
  out.error = lobe_error(e, data, s, rows.value);
  return out;
}

}  // namespace

std::vector<double> evaluate_rows(const expr::Expression& e, const std::vector<std::vector<double>>& columns) {
  std::vector<std::span<const double>> spans(columns.begin(), columns.end());
  std::vector<double> values(columns.empty() ? 0 : columns.front().size());
  expr::evaluate_batch(e, spans, values);
  return values;
}

std::vector<double> param_grid(double lo, double hi, std::size_t count) {
  std::vector<double> out;
  if (count == 1 || lo == hi) return {lo};
  const bool log = log_spaced(lo, hi);
  for (std::size_t i = 0; i < count; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(count - 1);
    out.push_back(i + 1 == count ? hi : log ? lo * std::pow(hi / lo, t) : lo + (hi - lo) * t);
  }
  return out;
}

namespace {

// One variable's values over (0, 1]: `count` even, and half as many again in t²/4, denser toward
// grazing (a cosine → 0), where Fresnel's and Smith's terms change fastest.
std::vector<double> axis(std::size_t count) {
  std::vector<double> out;
  for (std::size_t i = 1; i <= count; ++i) out.push_back(static_cast<double>(i) / count);
  for (std::size_t i = 1; i <= count / 2; ++i) out.push_back(std::pow(static_cast<double>(i) / (count / 2), 2) / 4);
  std::ranges::sort(out);
  return out;
}

// A function target's rows at p, filtered: finite, and for max_rel ≥ zone × the largest.
Samples function_samples_at(const Settings& s, double p) {
  const Samples all = function_rows(s, p);
  double top = 0;
  for (double v : all.value)
    if (std::isfinite(v)) top = std::max(top, v);
  const auto keep = [&](std::size_t r) {
    const double v = all.value[r];
    return std::isfinite(v) && (s.objective != Objective::max_rel || (v >= s.zone * top && v > 0));
  };
  Samples kept{p, {}, std::vector<std::vector<double>>(all.x.size()), {}};
  for (std::size_t r = 0; r < all.value.size(); ++r) {
    if (!keep(r)) continue;
    for (std::size_t v = 0; v < all.x.size(); ++v) kept.x[v].push_back(all.x[v][r]);
    kept.value.push_back(all.value[r]);
  }
  if (kept.value.empty()) throw InvalidField("target", fmt::format("the target has no usable row at {} = {:g}", s.param, p));
  return kept;
}

}  // namespace

std::vector<double> output_axis(const Settings& s) {
  std::vector<double> out;
  for (int i = 0; i < output_count(s.target); ++i) out.push_back(i);
  return out;
}

Samples function_rows(const Settings& s, double p) {
  const std::size_t k = s.variables.size();
  const std::size_t continuous = k - (output_count(s.target) > 1 ? 1 : 0);
  const std::vector<double> values = axis(continuous == 1 ? 86 : continuous == 2 ? 16 : 8);
  std::vector<std::vector<double>> axes(k, values);
  for (std::size_t v = 0; v < k; ++v)
    if (is_output_variable(s, v)) axes[v] = output_axis(s);
  Samples out{p, {}, std::vector<std::vector<double>>(k), {}};
  std::size_t rows = 1;
  for (const auto& a : axes) rows *= a.size();
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t v = 0, rest = r; v < k; rest /= axes[v].size(), ++v) out.x[v].push_back(axes[v][rest % axes[v].size()]);
  std::vector<std::vector<double>> columns = out.x;
  if (!s.param.empty()) columns.emplace_back(rows, p);
  out.value = target_values(s, columns);
  return out;
}

Samples samples_at(const Settings& s, double p) {
  if (is_function_target(s.target)) return function_samples_at(s, p);
  Samples out{p, target_at(s, p).lobe(), {{}}, {}};
  const double width = half_max_u(out.target);
  const auto add = [&](double u) {
    const double value = lobes::at_log_cos(out.target, u);
    if (!std::isfinite(value)) return;
    if (s.objective == Objective::max_rel && !(value >= s.zone)) return;
    out.x[0].push_back(std::exp(-u));
    out.value.push_back(value);
  };
  if (std::isfinite(width))
    for (std::size_t i = 0; i < kWidthRows; ++i) {
      const double t = static_cast<double>(i) / static_cast<double>(kWidthRows - 1);
      add(kWidths * width * t * t);  // denser near the peak
    }
  for (std::size_t i = 0; i < kUniformRows; ++i) {
    const double c = static_cast<double>(i) / static_cast<double>(kUniformRows - 1);
    add(c > 0 ? -std::log(c) : 745.0);
  }
  if (out.value.empty()) throw InvalidField("target", fmt::format("the target is nowhere ≥ the zone at {} = {:g}", s.param, p));
  return out;
}

double shape_error(const Shape& shape, std::span<const double> constants, const Samples& rows, const Settings& s) {
  return lobe_error(with_constants(shape, constants, s.variables), data_for(rows, {}, s.variables), s, rows.value);
}

namespace {

// Every grid value's rows as one data set: the per-pixel variables, then the parameter.
fit::Data joint_data(std::span<const Samples> grid, const Settings& s) {
  fit::Data data;
  data.variables = s.variables;
  data.variables.push_back(s.param);
  data.columns.resize(s.variables.size() + 1);
  for (const Samples& g : grid) {
    for (std::size_t v = 0; v < s.variables.size(); ++v) data.columns[v].insert(data.columns[v].end(), g.x[v].begin(), g.x[v].end());
    data.columns.back().insert(data.columns.back().end(), g.value.size(), g.param);
    data.target.insert(data.target.end(), g.value.begin(), g.value.end());
  }
  return data;
}

// Whether `lobe` is finite on the first grid value's rows at parameter values between and beyond
// the grid's (a refit may move a law's pole into the range).
bool finite_between(const expr::Expression& lobe, std::span<const Samples> grid, const Settings& s) {
  std::vector<std::vector<double>> columns = grid.front().x;
  const std::size_t rows = grid.front().value.size();
  columns.emplace_back(rows, 0.0);
  for (double p : param_grid(s.lo, s.hi, kDenseParams)) {
    std::ranges::fill(columns.back(), p);
    for (double v : evaluate_rows(lobe, columns))
      if (!std::isfinite(v)) return false;
  }
  return true;
}

}  // namespace

double expression_grid_error(const expr::Expression& lobe, std::span<const Samples> grid, const Settings& s) {
  double worst = 0;
  for (const Samples& g : grid) {
    fit::Data data = data_for(g, {}, s.variables);
    data.variables.push_back(s.param);
    data.columns.emplace_back(g.value.size(), g.param);
    worst = std::max(worst, lobe_error(lobe, data, s, g.value));
  }
  return std::isnan(worst) ? INFINITY : worst;
}

std::pair<expr::Expression, double> jointly_refitted(const expr::Expression& lobe, std::span<const Samples> grid,
                                                     const Settings& s) {
  const double before = expression_grid_error(lobe, grid, s);
  if (free_values(lobe).empty()) return {lobe, before};
  try {
    const expr::Expression refitted = fit::fit_formula_constants(lobe, joint_data(grid, s), metric_of(s)).formula;
    const double after = expression_grid_error(refitted, grid, s);
    if (after < before && finite_between(refitted, grid, s)) return {refitted, after};
  } catch (const InvalidArgument&) {  // more constants than a fit takes: the laws as they are
  }
  return {lobe, before};
}

std::string value_signature(const Shape& shape, std::span<const double> constants, const Samples& rows, const Settings& s) {
  const expr::Expression e = with_constants(shape, constants, s.variables);
  std::vector<double> point(s.variables.size());
  std::string out;
  for (std::size_t r = 0; r < rows.value.size(); r += 8) {
    for (std::size_t v = 0; v < point.size(); ++v) point[v] = rows.x[v][r];
    out += fmt::format("{:.6g},", expr::evaluate(e, point));
  }
  return out;
}

GridFit fit_over_grid(const Shape& shape, std::span<const Samples> grid, const Settings& s,
                      std::span<const std::vector<double>> fixed, const GridFit* started) {
  GridFit out = started ? *started : GridFit{};
  const auto fixed_at = [&](std::size_t i) { return fixed.empty() ? std::span<const double>() : std::span<const double>(fixed[i]); };
  std::mt19937_64 rng(s.seed ^ std::hash<std::string>{}(shape.key));
  const std::vector<double> identity = free_values(shape.expression(s.variables));  // every a·x + b at a = 1, b = 0
  std::vector<double> previous;  // the free constants of the last grid value
  const std::size_t first = out.constants.size();
  if (first > 0) previous.assign(out.constants.back().begin() + static_cast<std::ptrdiff_t>(fixed_at(first - 1).size()),
                                 out.constants.back().end());
  for (std::size_t i = first; i < grid.size(); ++i) {
    const std::size_t held = fixed_at(i).size();
    const std::vector<double> identity_free(identity.begin() + static_cast<std::ptrdiff_t>(held), identity.end());
    std::vector<std::vector<double>> starts{identity_free};
    if (!previous.empty()) starts.push_back(previous);
    if (i == 0 && !identity_free.empty())
      for (int k = 0; k < kRandomStarts; ++k) {
        std::vector<double> start;
        for (std::size_t j = 0; j < identity_free.size(); ++j)
          start.push_back((rng() & 1 ? 1 : -1) * std::exp(std::uniform_real_distribution<double>(-2, 4)(rng)));
        starts.push_back(std::move(start));
      }
    Fitted best;
    for (const auto& start : starts) {
      Fitted f = fit_once(shape, grid[i], s, fixed_at(i), start);
      if (f.error < best.error) best = std::move(f);
    }
    if (best.constants.empty()) best.constants = identity;
    previous.assign(best.constants.begin() + static_cast<std::ptrdiff_t>(held), best.constants.end());
    out.constants.push_back(best.constants);
    out.error.push_back(best.error);
  }
  out.worst = 0;
  for (double e : out.error) out.worst = std::max(out.worst, e);
  if (std::isnan(out.worst)) out.worst = INFINITY;
  return out;
}

}  // namespace specula::design
