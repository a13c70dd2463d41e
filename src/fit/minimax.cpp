// Minimax: a formula's constants for its largest error instead of its sum of squares, refining
// the least-squares fit of constants.cpp (docs/fit.md).
#include <algorithm>
#include <cmath>
#include <optional>

#include "projection.h"

namespace specula::fit {

using Eigen::MatrixXd;
using Eigen::VectorXd;

bool is_minimax(Metric metric) { return metric == Metric::max_abs || metric == Metric::max_rel; }

namespace {

using Eigen::Index;

constexpr int kLawsonRounds = 8;
constexpr int kExchangeSteps = 4;
constexpr int kMaxExchanges = 64;

// The errors B·δ − b levelled on a reference of B.cols() + 1 rows: (B·δ − b)_i = sign_i·h with
// h ≥ 0, the signs being those of the reference's dual weights λ (Σ λ_i·B_i = 0; `dual` holds
// |λ|). h is a lower bound of max |B·δ − b| over every δ (de la Vallée Poussin).
struct Levelled {
  VectorXd delta, sign, dual;
  double h = 0;
};

std::optional<Levelled> levelled(const MatrixXd& B, const VectorXd& b, const std::vector<Index>& reference) {
  const Index m = B.cols();
  const MatrixXd rows = B(reference, Eigen::all);
  const VectorXd null = Eigen::HouseholderQR<MatrixXd>(rows).householderQ() * VectorXd::Unit(m + 1, m);
  Levelled out;
  out.sign = null.unaryExpr([](double v) { return v < 0 ? -1.0 : 1.0; });
  out.dual = null.cwiseAbs();
  MatrixXd system(m + 1, m + 1);
  system << rows, -out.sign;
  const Eigen::FullPivLU<MatrixXd> lu(system);
  if (!lu.isInvertible()) return std::nullopt;
  const VectorXd solution = lu.solve(b(reference));
  out.delta = solution.head(m);
  out.h = solution(m);
  if (out.h < 0) {
    out.h = -out.h;
    out.sign = -out.sign;
  }
  return out;
}

// The reference row that leaves when row j enters with the sign of its error: writing
// sign_j·B_j = Σ ν_i·sign_i·B_i, the row of largest ν_i/λ_i, whose dual weight reaches 0 first
// as j's grows (the ratio test of the dual simplex method).
Index leaving(const MatrixXd& B, const Levelled& level, const std::vector<Index>& reference, Index j,
              double error) {
  const MatrixXd signed_rows = level.sign.asDiagonal() * B(reference, Eigen::all);
  const VectorXd entering = (error < 0 ? -1.0 : 1.0) * B.row(j).transpose();
  const VectorXd nu = signed_rows.transpose().completeOrthogonalDecomposition().solve(entering);
  Index out = 0;
  (nu.array() / level.dual.array().max(1e-300)).maxCoeff(&out);
  return out;
}

// δ minimizing max_r |B·δ − b|_r for B of full column rank with more rows than columns, by
// Stiefel's exchange algorithm from `reference` (left at the last one): each exchange brings in
// the row of the largest error, which raises h, until no error exceeds h (δ is then optimal) or
// h stops rising (rounding). nullopt where a reference is singular at once.
std::optional<VectorXd> chebyshev(const MatrixXd& B, const VectorXd& b, std::vector<Index>& reference) {
  std::optional<VectorXd> best;
  double best_error = INFINITY, last_h = -1;
  for (int exchange = 0; exchange < kMaxExchanges; ++exchange) {
    const auto level = levelled(B, b, reference);
    if (!level || !(level->h > last_h)) break;
    last_h = level->h;
    const VectorXd error = B * level->delta - b;
    Index worst = 0;
    const double largest = error.cwiseAbs().maxCoeff(&worst);
    if (largest < best_error) {
      best_error = largest;
      best = level->delta;
    }
    if (largest <= level->h * (1 + 1e-12) || std::ranges::find(reference, worst) != reference.end()) break;
    reference[static_cast<std::size_t>(leaving(B, *level, reference, worst, error(worst)))] = worst;
  }
  return best;
}

// B.cols() + 1 rows to start the exchange from: those a column-pivoted QR picks first among the
// rows of [B, sign(b)] scaled by √weight (Lawson's weights gather on the rows of largest error).
std::vector<Index> initial_reference(const MatrixXd& B, const VectorXd& b, const std::vector<double>& weight) {
  MatrixXd rows(B.cols() + 1, B.rows());
  for (Index r = 0; r < B.rows(); ++r) {
    const double w = std::sqrt(weight[static_cast<std::size_t>(r)]);
    rows.col(r) << w * B.row(r).transpose(), b(r) < 0 ? -w : w;
  }
  const Eigen::ColPivHouseholderQR<MatrixXd> qr(rows);
  const auto& pivots = qr.colsPermutation().indices();
  return std::vector<Index>(pivots.data(), pivots.data() + B.cols() + 1);
}

// The columns of J that a column-pivoted QR finds independent, ascending.
std::vector<Index> independent_columns(const MatrixXd& J) {
  Eigen::ColPivHouseholderQR<MatrixXd> qr(J);
  qr.setThreshold(1e-10);
  const auto& pivots = qr.colsPermutation().indices();
  std::vector<Index> columns(pivots.data(), pivots.data() + qr.rank());
  std::ranges::sort(columns);
  return columns;
}

// Refines a least-squares fit for the largest scaled error max_r s_r·|f_r − y_r| (s_r = 1, or
// 1/|y_r| for max_rel), keeping the constants of the lowest one seen.
class Minimax {
 public:
  Minimax(Projection& p, const Rows& rows, Metric metric) : p_(p), rows_(rows) {
    for (double y : rows.target) scale_.push_back(metric == Metric::max_rel ? 1 / std::abs(y) : 1.0);
    weight_.assign(rows.size(), 1.0);
    remember(largest_error());
  }

  // Finite errors on every row (for max_rel: no zero target).
  bool defined() const { return std::isfinite(best_error_); }

  // Lawson's algorithm (1961): least squares weighted by w_r·s_r², w_r multiplied by the row's
  // error every round. For a formula linear in its constants the largest error converges to the
  // minimax one, slowly; here it also moves the nonlinear constants (variable projection).
  void lawson() {
    for (int round = 0; round < kLawsonRounds && best_error_ > 0; ++round) {
      if (!reweight()) break;
      const double cost = p_.solve_linear();
      if (std::isfinite(cost) && p_.nonlinear_count() > 0) levenberg_marquardt(p_, cost);
      const double error = largest_error();
      if (!std::isfinite(error)) break;
      remember(error);
    }
  }

  // From the best constants, steps that solve the formula's linearization exactly for the
  // largest error (exact for constants that enter linearly), while they lower it.
  void exchange() {
    set_constants(best_constants_);
    largest_error();
    std::vector<Index> reference;
    for (int step = 0; step < kExchangeSteps && best_error_ > 0; ++step)
      if (!exchange_step(reference)) break;
  }

  void keep_best() { set_constants(best_constants_); }

 private:
  // Lawson's update, normalized to mean 1; false once every error is 0.
  bool reweight() {
    double total = 0;
    for (std::size_t r = 0; r < weight_.size(); ++r) {
      weight_[r] *= std::abs(error_[r]);
      total += weight_[r];
    }
    if (!(total > 0)) return false;
    fit_weight_.resize(weight_.size());
    for (std::size_t r = 0; r < weight_.size(); ++r) {
      weight_[r] *= static_cast<double>(weight_.size()) / total;
      fit_weight_[r] = weight_[r] * scale_[r] * scale_[r];
    }
    p_.set_weights(fit_weight_);
    return true;
  }

  bool exchange_step(std::vector<Index>& reference) {
    const MatrixXd J = scaled_jacobian();
    if (!J.allFinite()) return false;
    const auto columns = independent_columns(J);
    if (columns.empty() || columns.size() >= rows_.size()) return false;
    const MatrixXd B = J(Eigen::all, columns);
    const VectorXd b = -Eigen::Map<const VectorXd>(error_.data(), to_index(error_.size()));
    if (reference.size() != columns.size() + 1) reference = initial_reference(B, b, weight_);
    const auto delta = chebyshev(B, b, reference);
    return delta && take_step(*delta, columns);
  }

  // constants += δ (or half or a quarter of it: the formula is not linear in all of them) where
  // that lowers the largest error.
  bool take_step(const VectorXd& delta, const std::vector<Index>& columns) {
    const std::vector<double> start = constants();
    for (double fraction : {1.0, 0.5, 0.25}) {
      for (std::size_t j = 0; j < columns.size(); ++j) {
        const auto k = static_cast<std::size_t>(columns[j]);
        p_.constant(k) = start[k] + fraction * delta(to_index(j));
      }
      if (remember(largest_error())) return true;
    }
    set_constants(start);
    largest_error();
    return false;
  }

  // Evaluates the formula afresh: the scaled errors, and their largest (inf if one is not finite).
  double largest_error() {
    p_.evaluate();
    error_.resize(rows_.size());
    double largest = 0;
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      error_[r] = scale_[r] * (p_.value()[r] - rows_.target[r]);
      if (!std::isfinite(error_[r])) return INFINITY;
      largest = std::max(largest, std::abs(error_[r]));
    }
    return largest;
  }

  bool remember(double error) {
    if (!(error < best_error_)) return false;
    best_error_ = error;
    best_constants_ = constants();
    return true;
  }

  // s_r·∂f_r/∂c_k, as of the last evaluation.
  MatrixXd scaled_jacobian() const {
    MatrixXd J(to_index(rows_.size()), to_index(p_.constant_count()));
    for (std::size_t k = 0; k < p_.constant_count(); ++k)
      for (std::size_t r = 0; r < rows_.size(); ++r) J(to_index(r), to_index(k)) = scale_[r] * p_.derivative(k, r);
    return J;
  }

  std::vector<double> constants() const {
    std::vector<double> out;
    for (std::size_t k = 0; k < p_.constant_count(); ++k) out.push_back(p_.constant(k));
    return out;
  }
  void set_constants(const std::vector<double>& values) {
    for (std::size_t k = 0; k < values.size(); ++k) p_.constant(k) = values[k];
  }

  static Index to_index(std::size_t i) { return static_cast<Index>(i); }

  Projection& p_;
  const Rows& rows_;
  std::vector<double> scale_, weight_, fit_weight_, error_, best_constants_;
  double best_error_ = INFINITY;
};

}  // namespace

void fit_minimax(Projection& p, const Rows& rows, Metric metric) {
  Minimax minimax(p, rows, metric);
  if (!minimax.defined()) return;
  minimax.lawson();
  minimax.exchange();
  minimax.keep_best();
}

}  // namespace specula::fit
