#pragma once
// Variable projection over the constants of one genome (constants.cpp) and the minimax
// refinement built on it (minimax.cpp): private to src/fit.
#include <Eigen/Dense>
#include <span>
#include <vector>

#include "constants.h"

namespace specula::fit {

// Buffers reused from fit to fit on each thread: fitting allocates nothing once they are warm.
struct Workspace {
  std::vector<double> sqrt_w, value, gradient, saved_value, saved_gradient, saved_constants;
  Eigen::MatrixXd G, J, A;
  Eigen::VectorXd b, s, r, g, step;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> least_squares;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr;
  Eigen::MatrixXd Q;
  Eigen::LDLT<Eigen::MatrixXd> ldlt;
};

// Variable projection over the constants of one genome.
class Projection {
 public:
  Projection(Genome& g, const Rows& rows, Workspace& w);

  // Row weights for the least-squares fits from now on (empty: 1).
  void set_weights(std::span<const double> weights);

  std::size_t nonlinear_count() const { return nonlinear_.size(); }
  std::size_t constant_count() const { return constant_nodes_.size(); }
  double& constant(std::size_t k) { return g_[constant_nodes_[k]].value; }
  const std::vector<double>& value() const { return w_.value; }
  void evaluate() { evaluate_with_gradient(g_, rows_, w_.value, w_.gradient); }
  // ∂f/∂(constant k) in row r, as of the last evaluate().
  double derivative(std::size_t k, std::size_t r) const { return w_.gradient[k * rows_.size() + r]; }

  // Solves the linear constants for the current nonlinear ones; returns the weighted squared
  // error (inf if the formula is undefined on the rows).
  double solve_linear();
  // The damped Gauss-Newton step for the nonlinear constants, on the projected problem: the
  // Jacobian by the nonlinear constants loses its part in the span of the linear constants'
  // columns (Kaufman 1975), since the least-squares solve absorbs that part.
  const Eigen::VectorXd& step(double lambda);
  void move_nonlinear(const Eigen::VectorXd& step);
  void save();
  void restore();
  void round_constants();

 private:
  double solve_linear_change();
  void fill_columns(Eigen::MatrixXd& M, const std::vector<std::size_t>& which) const;
  double squared_error() const;

  Genome& g_;
  const Rows& rows_;
  Workspace& w_;
  std::vector<std::size_t> constant_nodes_, linear_, nonlinear_;
  double target_scale_ = 1;
};

// Levenberg–Marquardt on the nonlinear constants, each step re-solving the linear ones.
void levenberg_marquardt(Projection& p, double cost);

bool is_minimax(Metric metric);

// Refines p's least-squares fit for the largest error (max_abs, max_rel): Lawson's reweighted
// least squares, then Chebyshev exchange steps, keeping the constants of the lowest error seen.
void fit_minimax(Projection& p, const Rows& rows, Metric metric);

}  // namespace specula::fit
