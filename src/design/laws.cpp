#include "laws.h"

#include <algorithm>
#include <cmath>

#include "specula/fit/fit.h"

namespace specula::design {

using expr::Node;
using expr::Op;

namespace {

// Generations of each law's search: a budget in generations, so the result is the same for any
// machine and thread count.
constexpr std::int64_t kLawGenerations = 40;
constexpr int kLawMaxSize = 13;
constexpr double kLawSlack = 0.02;  // a law may raise the lobe's grid error by 2 %

fit::Options law_options(const Settings& s) {
  fit::Options o;
  o.operators = {Op::add, Op::sub, Op::mul, Op::div, Op::sqrt, Op::log};
  o.max_size = kLawMaxSize;
  o.metric = fit::Metric::max_abs;
  o.seed = s.seed;
  o.max_generations = kLawGenerations;
  o.time_limit_s = 120;
  o.threads = 1;
  o.islands = 2;
  o.population = 100;
  o.enumerate_max_size = 7;
  o.enumerate_limit = 3000;
  o.cancel = s.cancel;
  return o;
}

// Evaluates a law (an expression in the parameter) at p.
double law_at(const expr::Expression& law, double p) {
  const double x[] = {p};
  return expr::evaluate(law, x);
}

// Whether `law` is finite over the whole range and stays near its fitted values: within their
// span again beyond their smallest and largest (a pole between two grid values is neither).
bool law_holds(const expr::Expression& law, std::span<const double> fitted, const Settings& s) {
  const auto [lo, hi] = std::ranges::minmax(fitted);
  const double margin = std::max(hi - lo, 1e-9 * std::max(std::abs(lo), std::abs(hi)));
  for (double p : param_grid(s.lo, s.hi, kDenseParams)) {
    const double v = law_at(law, p);
    if (!(v >= lo - margin && v <= hi + margin)) return false;
  }
  return true;
}

double grid_error(const Shape& shape, std::span<const Samples> grid, const std::vector<std::vector<double>>& constants,
                  const Settings& s) {
  double worst = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) worst = std::max(worst, shape_error(shape, constants[i], grid[i], s));
  return std::isnan(worst) ? INFINITY : worst;
}

}  // namespace

expr::Expression substitute_laws(const Shape& shape, std::span<const expr::Expression> laws,
                                 const std::vector<std::string>& variables, const std::string& param) {
  std::vector<Node> nodes;
  std::size_t k = 0;
  for (const auto& n : shape.nodes) {
    if (n.op == Op::constant && !expr::is_exact(n)) {
      for (Node m : laws[k].nodes()) {
        if (m.op == Op::variable) m.var = static_cast<std::uint32_t>(variables.size());  // the parameter, after the variables
        nodes.push_back(m);
      }
      ++k;
    } else {
      nodes.push_back(n);
    }
  }
  std::vector<std::string> names = variables;
  names.push_back(param);
  return expr::Expression(std::move(nodes), std::move(names));
}

std::optional<Lawful> constant_laws(const Shape& shape, std::span<const Samples> grid, const GridFit& fitted,
                                    const Settings& s, const std::function<bool()>& stop) {
  if (s.param.empty())  // no parameter: the constants are numbers
    return Lawful{with_constants(shape, fitted.constants.at(0), s.variables), fitted.worst};
  std::vector<double> params;
  for (const auto& g : grid) params.push_back(g.param);
  std::vector<std::vector<double>> constants = fitted.constants;
  std::vector<expr::Expression> laws;
  const auto constant_count = static_cast<std::size_t>(shape.constants);
  const double optimum = grid_error(shape, grid, constants, s);
  const double within = optimum * (1 + kLawSlack);
  // The constants after k refitted per value with 0 … k held at `values`.
  const auto refit_after = [&](std::size_t k, const std::vector<std::vector<double>>& values) {
    std::vector<std::vector<double>> held;
    for (const auto& c : values) held.emplace_back(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(k + 1));
    return k + 1 < constant_count ? fit_over_grid(shape, grid, s, held).constants : values;
  };
  for (std::size_t k = 0; k < constant_count; ++k) {
    if (stop()) return std::nullopt;
    // A constant the others make up for (a scale that a later affine step repeats) is held at one
    // value, its median, when the others refitted keep the lobe within the slack: its values over
    // the grid wander between equally good fits, which no small law follows.
    std::vector<double> column;
    for (const auto& c : constants) column.push_back(c[k]);
    std::ranges::nth_element(column, column.begin() + static_cast<std::ptrdiff_t>(column.size() / 2));
    const double median = column[column.size() / 2];
    auto one_value = constants;
    for (auto& c : one_value) c[k] = median;
    one_value = refit_after(k, one_value);
    if (std::isfinite(median) && grid_error(shape, grid, one_value, s) <= within) {
      laws.push_back(expr::Expression({{Op::constant, 0, median}}, {s.param}));
      constants = std::move(one_value);
      continue;
    }
    fit::Data data{{s.param}, {params}, {}};
    for (const auto& c : constants) data.target.push_back(c[k]);
    const fit::Result found = fit::search(data, law_options(s));
    if (found.stopped_by == fit::StopReason::cancelled) return std::nullopt;
    // The first formula (smallest) whose lobe is within the slack of the per-value optimum, else
    // the most accurate one.
    std::optional<expr::Expression> chosen;
    std::vector<std::vector<double>> chosen_constants;
    double chosen_error = INFINITY;
    for (const auto& candidate : found.front) {
      if (!law_holds(candidate.formula, data.target, s)) continue;
      auto trial = constants;
      for (std::size_t i = 0; i < grid.size(); ++i) trial[i][k] = law_at(candidate.formula, params[i]);
      const double error = grid_error(shape, grid, trial, s);
      if (error < chosen_error) {
        chosen = candidate.formula;
        chosen_constants = std::move(trial);
        chosen_error = error;
      }
      if (chosen_error <= within) break;
    }
    if (!chosen) return std::nullopt;
    laws.push_back(*chosen);
    constants = refit_after(k, chosen_constants);
  }
  auto [lobe, error] = jointly_refitted(substitute_laws(shape, laws, s.variables, s.param), grid, s);
  return Lawful{std::move(lobe), error};
}

}  // namespace specula::design
