// Constant fitting: variable projection (linear constants solved exactly, the others by
// Levenberg–Marquardt on the projected problem), then the minimax refinement (minimax.cpp) for
// the largest-error metrics. Derivatives: gradient.cpp.
#include "constants.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "projection.h"

namespace specula::fit {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

constexpr int kMaxIterations = 30;

}  // namespace

Projection::Projection(Genome& g, const Rows& rows, Workspace& w) : g_(g), rows_(rows), w_(w) {
  for (std::size_t i = 0; i < g.size(); ++i)
    if (is_free_constant(g[i])) constant_nodes_.push_back(i);
  const auto linear = linear_constants(g);
  for (std::size_t k = 0; k < linear.size(); ++k) (linear[k] ? linear_ : nonlinear_).push_back(k);
  for (double y : rows.target) target_scale_ = std::max(target_scale_, std::abs(y));
  w_.sqrt_w.assign(rows.size(), 1.0);
  set_weights(rows.weights);
}

void Projection::set_weights(std::span<const double> weights) {
  for (std::size_t r = 0; r < weights.size(); ++r) w_.sqrt_w[r] = std::sqrt(weights[r]);
}

double Projection::solve_linear() {
  for (int pass = 0; pass < 3; ++pass) {
    evaluate();
    if (!all_finite(w_.value) || !all_finite(w_.gradient)) return INFINITY;
    if (linear_.empty()) break;
    const double jump = solve_linear_change();
    if (!std::isfinite(jump)) return INFINITY;
    // Values moved by far more than the data carry the rounding of the move: once more
    // from the new point.
    if (jump <= 1e3 * target_scale_) break;
  }
  return squared_error();
}

// Moves the linear constants by the least-squares change δ for the current residuals (the
// formula is affine in them, so its values move by G·δ exactly); returns max |G·δ|.
double Projection::solve_linear_change() {
  const std::size_t n = rows_.size();
  fill_columns(w_.G, linear_);
  w_.b.resize(static_cast<Eigen::Index>(n));
  for (std::size_t r = 0; r < n; ++r)
    w_.b(static_cast<Eigen::Index>(r)) = w_.sqrt_w[r] * (rows_.target[r] - w_.value[r]);
  w_.least_squares.compute(w_.G);
  w_.s = w_.least_squares.solve(w_.b);
  if (!w_.s.allFinite()) return INFINITY;
  double jump = 0;
  for (std::size_t r = 0; r < n; ++r) {
    double move = 0;
    for (std::size_t j = 0; j < linear_.size(); ++j)
      move += w_.s(static_cast<Eigen::Index>(j)) * derivative(linear_[j], r);
    w_.value[r] += move;
    jump = std::max(jump, std::abs(move));
  }
  for (std::size_t j = 0; j < linear_.size(); ++j) constant(linear_[j]) += w_.s(static_cast<Eigen::Index>(j));
  return jump;
}

const VectorXd& Projection::step(double lambda) {
  fill_columns(w_.J, nonlinear_);
  if (!linear_.empty()) {
    fill_columns(w_.G, linear_);
    w_.qr.compute(w_.G);
    w_.Q = w_.qr.householderQ() * MatrixXd::Identity(w_.G.rows(), w_.G.cols());
    w_.J -= w_.Q * (w_.Q.transpose() * w_.J);
  }
  w_.r.resize(static_cast<Eigen::Index>(rows_.size()));
  for (std::size_t i = 0; i < rows_.size(); ++i)
    w_.r(static_cast<Eigen::Index>(i)) = w_.sqrt_w[i] * (rows_.target[i] - w_.value[i]);
  w_.A.noalias() = w_.J.transpose() * w_.J;
  w_.g.noalias() = w_.J.transpose() * w_.r;
  for (Eigen::Index i = 0; i < w_.A.rows(); ++i) w_.A(i, i) += lambda * std::max(w_.A(i, i), 1e-12);
  w_.ldlt.compute(w_.A);
  w_.step = w_.ldlt.solve(w_.g);
  return w_.step;
}

void Projection::move_nonlinear(const VectorXd& step) {
  for (std::size_t j = 0; j < nonlinear_.size(); ++j)
    constant(nonlinear_[j]) += step(static_cast<Eigen::Index>(j));
}

void Projection::save() {
  w_.saved_constants.clear();
  for (std::size_t k = 0; k < constant_count(); ++k) w_.saved_constants.push_back(constant(k));
  w_.saved_value = w_.value;
  w_.saved_gradient = w_.gradient;
}

void Projection::restore() {
  for (std::size_t k = 0; k < constant_count(); ++k) constant(k) = w_.saved_constants[k];
  std::swap(w_.value, w_.saved_value);
  std::swap(w_.gradient, w_.saved_gradient);
}

void Projection::round_constants() {
  for (std::size_t k = 0; k < constant_count(); ++k) constant(k) = std::round(constant(k));
}

// M's columns: the weighted derivatives by the constants `which`.
void Projection::fill_columns(MatrixXd& M, const std::vector<std::size_t>& which) const {
  M.resize(static_cast<Eigen::Index>(rows_.size()), static_cast<Eigen::Index>(which.size()));
  for (std::size_t j = 0; j < which.size(); ++j)
    for (std::size_t r = 0; r < rows_.size(); ++r)
      M(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j)) = w_.sqrt_w[r] * derivative(which[j], r);
}

double Projection::squared_error() const {
  double sum = 0;
  for (std::size_t r = 0; r < rows_.size(); ++r) {
    const double e = w_.sqrt_w[r] * (rows_.target[r] - w_.value[r]);
    sum += e * e;
  }
  return sum;
}

void levenberg_marquardt(Projection& p, double cost) {
  double lambda = 1e-3;
  for (int iteration = 0; iteration < kMaxIterations && lambda < 1e12; ++iteration) {
    const VectorXd& step = p.step(lambda);
    if (!step.allFinite()) break;
    p.save();
    p.move_nonlinear(step);
    const double trial = p.solve_linear();
    if (trial < cost) {
      const bool converged = cost - trial <= 1e-13 * cost;
      cost = trial;
      p.evaluate();  // derivatives at the new linear constants
      lambda *= 0.3;
      if (converged) break;
    } else {
      p.restore();
      lambda *= 10;
    }
  }
}

namespace {

std::vector<double> fitted_values(Genome& g, const Rows& rows, Constants mode, Metric metric) {
  thread_local Workspace workspace;
  Projection p(g, rows, workspace);
  const double cost = p.solve_linear();
  if (std::isfinite(cost) && p.nonlinear_count() > 0) levenberg_marquardt(p, cost);
  if (std::isfinite(cost) && is_minimax(metric) && p.constant_count() > 0) fit_minimax(p, rows, metric);
  if (mode == Constants::integer) p.round_constants();
  // Afresh: the values updated in place by the linear solves carry the cancellation error of
  // any large change in the linear constants.
  if (p.constant_count() > 0) p.evaluate();
  return p.value();
}

/// Whether the subtree [first, last] of g is negative on some row (at its current constants).
bool negative_somewhere(const Genome& g, std::size_t first, std::size_t last, const Rows& rows) {
  thread_local std::vector<double> value, gradient;
  evaluate_with_gradient(std::span<const expr::Node>(g.data() + first, last - first + 1), rows, value, gradient);
  return std::ranges::any_of(value, [](double v) { return v < 0; });
}

/// A real power of a negative number needs an integer exponent: a free constant exponent whose
/// base is negative on some row (x^c, c free, x < 0) is undefined there for every c but the
/// integers, and its derivative (the base's log) everywhere there, so no fit could start. It
/// becomes the nearest integer, held fixed (a mutation frees it again); returns where.
std::vector<std::size_t> hold_integer_exponents(Genome& g, const Rows& rows) {
  constexpr double kLargest = 1000;
  std::vector<std::size_t> starts, held;
  for (std::size_t i = 1; i < g.size(); ++i) {
    if (g[i].op != expr::Op::pow || !is_free_constant(g[i - 1])) continue;
    if (starts.empty()) starts = subtree_starts(g);
    if (!negative_somewhere(g, starts[i - 2], i - 2, rows)) continue;
    const double exponent = std::clamp(std::round(g[i - 1].value), -kLargest, kLargest);
    if (!std::isfinite(exponent)) continue;
    g[i - 1] = expr::exact_constant(static_cast<int>(exponent), 1, expr::Symbol::one);
    held.push_back(i - 1);
  }
  return held;
}

bool has_finite_constants(const Genome& g) {
  return std::ranges::all_of(g, [](const expr::Node& n) { return n.op != expr::Op::constant || std::isfinite(n.value); });
}

/// The fit from g's constants; on a fit that leaves a constant infinite (a linear solve over a
/// degenerate column, a step that overflowed) the constants go back and every prediction is NaN.
std::vector<double> fitted_or_nan(Genome& g, const Rows& rows, Constants mode, Metric metric) {
  thread_local std::vector<double> before;  // every evaluation fits: no allocation each time
  before.clear();
  for (const expr::Node& n : g) before.push_back(n.value);
  std::vector<double> predicted = fitted_values(g, rows, mode, metric);
  if (has_finite_constants(g)) return predicted;
  for (std::size_t i = 0; i < g.size(); ++i) g[i].value = before[i];
  return std::vector<double>(rows.size(), std::numeric_limits<double>::quiet_NaN());
}

double error_of(std::span<const double> predicted, const Rows& rows, Metric metric) {
  const double error = measure(metric, predicted, rows.target);
  return std::isnan(error) ? INFINITY : error;
}

/// A held integer exponent is a discrete constant, and the fit its line search: from the nearest
/// integer it steps by the first of +1, −1, +2, −2 that lowers the error, and on by the same step
/// while that lowers it (x^3 to x^9 in four fits: ±2 keeps an odd or even power's symmetry, which
/// ±1 breaks on data of both signs). Where mutations alone had to land on 9. At most kStepped
/// exponents per formula (each try is a whole fit), at most kSteps steps each.
std::vector<double> stepped_exponents(Genome& g, std::vector<double> predicted, std::span<const std::size_t> held,
                                      const Rows& rows, Constants mode, Metric metric) {
  constexpr std::size_t kStepped = 2;
  constexpr int kSteps = 12, kLargest = 64;
  if (held.size() > kStepped) return predicted;
  double error = error_of(predicted, rows, metric);
  const auto improved = [&](std::size_t at, int step) {
    const int exponent = static_cast<int>(g[at].value) + step;
    if (std::abs(exponent) > kLargest) return false;
    Genome trial = g;
    trial[at] = expr::exact_constant(exponent, 1, expr::Symbol::one);
    std::vector<double> values = fitted_or_nan(trial, rows, mode, metric);
    const double trial_error = error_of(values, rows, metric);
    if (!(trial_error < error * (1 - 1e-9))) return false;  // lower by more than rounding
    g = std::move(trial), predicted = std::move(values), error = trial_error;
    return true;
  };
  for (const std::size_t at : held)
    for (const int step : {1, -1, 2, -2}) {
      int taken = 0;
      while (taken < kSteps && improved(at, step)) ++taken;
      if (taken > 0) break;
    }
  return predicted;
}

}  // namespace

std::vector<double> fit_constants(Genome& g, const Rows& rows, Constants mode, Metric metric) {
  const std::vector<std::size_t> held = hold_integer_exponents(g, rows);
  std::vector<double> predicted = fitted_or_nan(g, rows, mode, metric);
  return held.empty() ? predicted : stepped_exponents(g, std::move(predicted), held, rows, mode, metric);
}
FittedFormula fit_formula_constants(const expr::Expression& formula, const Data& data, Metric metric) {
  if (data.target.empty()) throw InvalidArgument("no data rows");
  if (data.columns.size() != formula.variables().size())
    throw InvalidArgument(fmt::format("the formula reads {} variables, the data has {} columns",
                                      formula.variables().size(), data.columns.size()));
  const bool relative = metric == Metric::mean_relative || metric == Metric::max_rel;
  Rows rows;
  for (const auto& column : data.columns) {
    if (column.size() != data.target.size()) throw InvalidArgument("every column needs one value per target row");
    if (!std::ranges::all_of(column, [](double x) { return std::isfinite(x); }))
      throw InvalidArgument("the data holds a value that is not a finite number");
    rows.columns.emplace_back(column);
  }
  for (double y : data.target)
    if (!std::isfinite(y) || (relative && y == 0))
      throw InvalidArgument("a target value is not finite (or is 0 under a relative metric)");
  rows.target = data.target;
  if (relative)
    for (double y : data.target) rows.weights.push_back(1 / (y * y));
  Genome g(formula.nodes().begin(), formula.nodes().end());
  if (std::ranges::count_if(g, is_free_constant) > static_cast<std::ptrdiff_t>(kMaxConstants))
    throw InvalidArgument(fmt::format("more than {} constants", kMaxConstants));
  const auto predicted = fit_constants(g, rows, Constants::fitted, metric);
  double error = measure(metric, predicted, data.target);
  if (std::isnan(error)) error = INFINITY;
  return {expr::Expression(std::move(g), formula.variables()), error};
}

}  // namespace specula::fit
