// Constant fitting: forward-mode derivatives over row chunks, then variable projection.
#include "constants.h"

#include <Eigen/Dense>
#include <algorithm>
#include <bit>
#include <fmt/format.h>
#include <cmath>
#include <numbers>
#include <optional>

namespace specula::fit {

using expr::Node;
using expr::Op;

namespace {

constexpr std::size_t kChunk = 128;

struct Partials {
  double value, da, db;
};

// f(a, b) and its partial derivatives; unary ops ignore b.
template <Op op>
Partials apply(double a, double b) {
  if constexpr (op == Op::add) return {a + b, 1, 1};
  if constexpr (op == Op::sub) return {a - b, 1, -1};
  if constexpr (op == Op::mul) return {a * b, b, a};
  if constexpr (op == Op::div) return {a / b, 1 / b, -a / (b * b)};
  if constexpr (op == Op::pow) {
    const double v = std::pow(a, b);
    return {v, b * std::pow(a, b - 1), a > 0 ? v * std::log(a) : 0};
  }
  if constexpr (op == Op::min) return b < a ? Partials{b, 0, 1} : Partials{a, 1, 0};
  if constexpr (op == Op::max) return a < b ? Partials{b, 0, 1} : Partials{a, 1, 0};
  if constexpr (op == Op::neg) return {-a, -1, 0};
  if constexpr (op == Op::log) return {std::log(a), 1 / a, 0};
  if constexpr (op == Op::log2) return {std::log2(a), 1 / (a * std::numbers::ln2), 0};
  if constexpr (op == Op::exp) {
    const double v = std::exp(a);
    return {v, v, 0};
  }
  if constexpr (op == Op::sqrt) {
    const double v = std::sqrt(a);
    return {v, 0.5 / v, 0};
  }
  if constexpr (op == Op::abs) return {std::abs(a), a < 0 ? -1.0 : 1.0, 0};
  if constexpr (op == Op::sin) return {std::sin(a), std::cos(a), 0};
  if constexpr (op == Op::cos) return {std::cos(a), -std::sin(a), 0};
  if constexpr (op == Op::acos) return {std::acos(a), -1 / std::sqrt(1 - a * a), 0};
  if constexpr (op == Op::expm1) return {std::expm1(a), std::exp(a), 0};
  if constexpr (op == Op::log1p) return {std::log1p(a), 1 / (1 + a), 0};
  if constexpr (op == Op::asin) return {std::asin(a), 1 / std::sqrt(1 - a * a), 0};
  return {0, 0, 0};
}

// Values and partials of `op` over n rows: a ← f(a, b), da, db ← ∂f/∂a, ∂f/∂b.
template <Op op>
void apply_rows(std::size_t n, double* a, const double* b, double* da, double* db) {
  for (std::size_t i = 0; i < n; ++i) {
    const Partials p = apply<op>(a[i], b ? b[i] : 0.0);
    a[i] = p.value;
    da[i] = p.da;
    db[i] = p.db;
  }
}

void apply_rows(Op op, std::size_t n, double* a, const double* b, double* da, double* db) {
  switch (op) {
    case Op::add: return apply_rows<Op::add>(n, a, b, da, db);
    case Op::sub: return apply_rows<Op::sub>(n, a, b, da, db);
    case Op::mul: return apply_rows<Op::mul>(n, a, b, da, db);
    case Op::div: return apply_rows<Op::div>(n, a, b, da, db);
    case Op::pow: return apply_rows<Op::pow>(n, a, b, da, db);
    case Op::min: return apply_rows<Op::min>(n, a, b, da, db);
    case Op::max: return apply_rows<Op::max>(n, a, b, da, db);
    case Op::neg: return apply_rows<Op::neg>(n, a, b, da, db);
    case Op::log: return apply_rows<Op::log>(n, a, b, da, db);
    case Op::log2: return apply_rows<Op::log2>(n, a, b, da, db);
    case Op::exp: return apply_rows<Op::exp>(n, a, b, da, db);
    case Op::sqrt: return apply_rows<Op::sqrt>(n, a, b, da, db);
    case Op::abs: return apply_rows<Op::abs>(n, a, b, da, db);
    case Op::sin: return apply_rows<Op::sin>(n, a, b, da, db);
    case Op::cos: return apply_rows<Op::cos>(n, a, b, da, db);
    case Op::acos: return apply_rows<Op::acos>(n, a, b, da, db);
    case Op::expm1: return apply_rows<Op::expm1>(n, a, b, da, db);
    case Op::log1p: return apply_rows<Op::log1p>(n, a, b, da, db);
    case Op::asin: return apply_rows<Op::asin>(n, a, b, da, db);
    case Op::constant:
    case Op::variable: return;
  }
}

// The evaluation stack for one chunk: slot s holds a value block and a derivative block per
// constant, each kChunk long. Only the blocks of the constants in depends(s) (a bit set) are
// meaningful; the others are zero by definition.
class ChunkStack {
 public:
  void reset(std::size_t depth, std::size_t constants) {
    blocks_ = constants + 1;
    if (data_.size() < depth * blocks_ * kChunk) data_.resize(depth * blocks_ * kChunk);
    depends_.resize(depth);
  }
  double* value(std::size_t slot) { return &data_[slot * blocks_ * kChunk]; }
  double* gradient(std::size_t slot, std::size_t k) { return value(slot) + (k + 1) * kChunk; }
  std::uint64_t& depends(std::size_t slot) { return depends_[slot]; }

 private:
  std::size_t blocks_ = 1;
  std::vector<double> data_;
  std::vector<std::uint64_t> depends_;
};

std::size_t stack_depth(std::span<const Node> nodes) {
  std::size_t top = 0, depth = 0;
  for (const Node& n : nodes) {
    top = top + 1 - static_cast<std::size_t>(expr::arity(n.op));
    depth = std::max(depth, top);
  }
  return depth;
}

void push_leaf(ChunkStack& s, std::size_t slot, const Node& node, std::size_t constant_index,
               const Rows& rows, std::size_t first, std::size_t n) {
  double* v = s.value(slot);
  if (node.op == Op::variable) {
    std::copy_n(rows.columns[node.var].data() + first, n, v);
    s.depends(slot) = 0;
    return;
  }
  std::fill_n(v, n, node.value);
  if (expr::is_exact(node)) {  // held fixed: no derivative
    s.depends(slot) = 0;
    return;
  }
  std::fill_n(s.gradient(slot, constant_index), n, 1.0);
  s.depends(slot) = std::uint64_t{1} << constant_index;
}

// Applies `op` to slots a (and b = a + 1), leaving the result in slot a: the chain rule over
// the constants either operand depends on.
void apply_op(ChunkStack& s, Op op, std::size_t a, std::size_t n) {
  const bool binary = expr::arity(op) == 2;
  std::array<double, kChunk> da, db;
  apply_rows(op, n, s.value(a), binary ? s.value(a + 1) : nullptr, da.data(), db.data());
  const std::uint64_t in_a = s.depends(a), in_b = binary ? s.depends(a + 1) : 0;
  for (std::uint64_t left = in_a | in_b; left != 0; left &= left - 1) {
    const auto k = static_cast<std::size_t>(std::countr_zero(left));
    const std::uint64_t bit = std::uint64_t{1} << k;
    double* ka = s.gradient(a, k);
    const double* kb = binary ? s.gradient(a + 1, k) : nullptr;
    if (!(in_b & bit))
      for (std::size_t i = 0; i < n; ++i) ka[i] *= da[i];
    else if (in_a & bit)
      for (std::size_t i = 0; i < n; ++i) ka[i] = ka[i] * da[i] + kb[i] * db[i];
    else
      for (std::size_t i = 0; i < n; ++i) ka[i] = kb[i] * db[i];
  }
  s.depends(a) = in_a | in_b;
}

}  // namespace

void evaluate_with_gradient(std::span<const Node> nodes, const Rows& rows,
                            std::vector<double>& value, std::vector<double>& gradient) {
  const std::size_t count = rows.size();
  const auto constants = static_cast<std::size_t>(std::count_if(nodes.begin(), nodes.end(), is_free_constant));
  if (constants > kMaxConstants)
    throw InvalidArgument(fmt::format("a formula may have at most {} constants", kMaxConstants));
  value.resize(count);
  gradient.assign(constants * count, 0);
  thread_local ChunkStack s;
  s.reset(stack_depth(nodes), constants);
  for (std::size_t first = 0; first < count; first += kChunk) {
    const std::size_t n = std::min(kChunk, count - first);
    std::size_t top = 0, constant_index = 0;
    for (const Node& node : nodes) {
      const int operands = expr::arity(node.op);
      if (operands == 0) {
        push_leaf(s, top++, node, is_free_constant(node) ? constant_index++ : constants, rows, first, n);
      } else {
        top -= static_cast<std::size_t>(operands);
        apply_op(s, node.op, top++, n);
      }
    }
    std::copy_n(s.value(0), n, value.data() + first);
    for (std::uint64_t left = s.depends(0); left != 0; left &= left - 1) {
      const auto k = static_cast<std::size_t>(std::countr_zero(left));
      std::copy_n(s.gradient(0, k), n, gradient.data() + k * count + first);
    }
  }
}

namespace {

// Whether the formula is affine in the constants marked in `chosen` (indexed by node).
bool affine_in(std::span<const Node> nodes, const std::vector<bool>& chosen) {
  std::vector<bool> depends;  // stack: does the operand involve a chosen constant?
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Op op = nodes[i].op;
    const int operands = expr::arity(op);
    if (operands == 0) {
      depends.push_back(chosen[i]);
      continue;
    }
    const bool b = operands == 2 && depends.back();
    if (operands == 2) depends.pop_back();
    const bool a = depends.back();
    const bool linear_op = op == Op::add || op == Op::sub || op == Op::neg ||
                           (op == Op::mul && !(a && b)) || (op == Op::div && !b);
    if ((a || b) && !linear_op) return false;
    depends.back() = a || b;
  }
  return true;
}

}  // namespace

std::vector<bool> linear_constants(std::span<const Node> nodes) {
  std::vector<bool> chosen(nodes.size(), false);
  std::vector<bool> linear;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!is_free_constant(nodes[i])) continue;
    chosen[i] = true;
    if (!affine_in(nodes, chosen)) chosen[i] = false;
    linear.push_back(chosen[i]);
  }
  return linear;
}

namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

bool all_finite(const std::vector<double>& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

// Buffers reused from fit to fit on each thread: fitting allocates nothing once they are warm.
struct Workspace {
  std::vector<double> sqrt_w, value, gradient, saved_value, saved_gradient, saved_constants;
  MatrixXd G, J, A;
  VectorXd b, s, r, g, step;
  Eigen::CompleteOrthogonalDecomposition<MatrixXd> least_squares;
  Eigen::HouseholderQR<MatrixXd> qr;
  MatrixXd Q;
  Eigen::LDLT<MatrixXd> ldlt;
};

// Variable projection over the constants of one genome.
class Projection {
 public:
  Projection(Genome& g, const Rows& rows, Workspace& w) : g_(g), rows_(rows), w_(w) {
    for (std::size_t i = 0; i < g.size(); ++i)
      if (is_free_constant(g[i])) constant_nodes_.push_back(i);
    const auto linear = linear_constants(g);
    for (std::size_t k = 0; k < linear.size(); ++k) (linear[k] ? linear_ : nonlinear_).push_back(k);
    for (double y : rows.target) target_scale_ = std::max(target_scale_, std::abs(y));
    w_.sqrt_w.assign(rows.size(), 1.0);
    set_weights(rows.weights);
  }

  // Row weights for the least-squares fits from now on (empty: 1).
  void set_weights(std::span<const double> weights) {
    for (std::size_t r = 0; r < weights.size(); ++r) w_.sqrt_w[r] = std::sqrt(weights[r]);
  }

  std::size_t nonlinear_count() const { return nonlinear_.size(); }
  std::size_t constant_count() const { return constant_nodes_.size(); }
  double& constant(std::size_t k) { return g_[constant_nodes_[k]].value; }
  const std::vector<double>& value() const { return w_.value; }
  void evaluate() { evaluate_with_gradient(g_, rows_, w_.value, w_.gradient); }
  // ∂f/∂(constant k) in row r, as of the last evaluate().
  double derivative(std::size_t k, std::size_t r) const { return w_.gradient[k * rows_.size() + r]; }

  // Solves the linear constants for the current nonlinear ones; returns the weighted squared
  // error (inf if the formula is undefined on the rows).
  double solve_linear() {
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
  double solve_linear_change() {
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

  // The damped Gauss-Newton step for the nonlinear constants, on the projected problem: the
  // Jacobian by the nonlinear constants loses its part in the span of the linear constants'
  // columns (Kaufman 1975), since the least-squares solve absorbs that part.
  const VectorXd& step(double lambda) {
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

  void move_nonlinear(const VectorXd& step) {
    for (std::size_t j = 0; j < nonlinear_.size(); ++j)
      constant(nonlinear_[j]) += step(static_cast<Eigen::Index>(j));
  }

  void save() {
    w_.saved_constants.clear();
    for (std::size_t k = 0; k < constant_count(); ++k) w_.saved_constants.push_back(constant(k));
    w_.saved_value = w_.value;
    w_.saved_gradient = w_.gradient;
  }
  void restore() {
    for (std::size_t k = 0; k < constant_count(); ++k) constant(k) = w_.saved_constants[k];
    std::swap(w_.value, w_.saved_value);
    std::swap(w_.gradient, w_.saved_gradient);
  }

  void round_constants() {
    for (std::size_t k = 0; k < constant_count(); ++k) constant(k) = std::round(constant(k));
  }

 private:
  // M's columns: the weighted derivatives by the constants `which`.
  void fill_columns(MatrixXd& M, const std::vector<std::size_t>& which) const {
    M.resize(static_cast<Eigen::Index>(rows_.size()), static_cast<Eigen::Index>(which.size()));
    for (std::size_t j = 0; j < which.size(); ++j)
      for (std::size_t r = 0; r < rows_.size(); ++r)
        M(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j)) = w_.sqrt_w[r] * derivative(which[j], r);
  }

  double squared_error() const {
    double sum = 0;
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      const double e = w_.sqrt_w[r] * (rows_.target[r] - w_.value[r]);
      sum += e * e;
    }
    return sum;
  }

  Genome& g_;
  const Rows& rows_;
  Workspace& w_;
  std::vector<std::size_t> constant_nodes_, linear_, nonlinear_;
  double target_scale_ = 1;
};

constexpr int kMaxIterations = 30;

// Levenberg–Marquardt on the nonlinear constants, each step re-solving the linear ones.
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

// Minimax: constants for the largest error instead of the sum of squares.

using Eigen::Index;

constexpr int kLawsonRounds = 8;
constexpr int kExchangeSteps = 4;
constexpr int kMaxExchanges = 64;

bool is_minimax(Metric metric) { return metric == Metric::max_abs || metric == Metric::max_rel; }

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

void fit_minimax(Projection& p, const Rows& rows, Metric metric) {
  Minimax minimax(p, rows, metric);
  if (!minimax.defined()) return;
  minimax.lawson();
  minimax.exchange();
  minimax.keep_best();
}

}  // namespace

std::vector<double> fit_constants(Genome& g, const Rows& rows, Constants mode, Metric metric) {
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
