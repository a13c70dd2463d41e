#include "transformed.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>

#include "expanded.h"

namespace specula::fit {
namespace {

using expr::Node;
using expr::Op;

constexpr std::size_t kMostMonomials = 16;
constexpr std::size_t kMostRationalMonomials = 32;  // of P and Q together
constexpr int kMostRatioDegree = 8;  // of P and of Q: binds in one variable only, where pairs abound
constexpr std::size_t kMostRows = 512;  // the search refits a formula found on all the rows
constexpr double kExact = 1e-9;       // a fit's residual, relative to the target's norm, at rounding
constexpr double kNegligible = 1e-8;  // a term whose part of the target's norm is rounding
constexpr double kUnit = 1e-9;        // a coefficient this close to ±1 is written bare

// The function that makes the formula of the polynomial P: y = P, exp(P), log(P).
enum class Outer { none, exp, log };

struct Term {
  std::vector<int> exponents;
  double coefficient;
};

bool is_constant(const Term& t) {
  return std::ranges::all_of(t.exponents, [](int e) { return e == 0; });
}

// The rows the polynomials are fitted on: all of them, or kMostRows evenly spaced.
std::vector<std::size_t> picked_rows(std::size_t n) {
  const std::size_t m = std::min(n, kMostRows);
  std::vector<std::size_t> out(m);
  for (std::size_t i = 0; i < m; ++i) out[i] = i * n / m;
  return out;
}

std::size_t distinct_points(const Rows& rows, const std::vector<std::size_t>& picked) {
  std::vector<std::vector<double>> points;
  for (std::size_t r : picked) {
    std::vector<double> p;
    for (const auto& column : rows.columns) p.push_back(column[r]);
    points.push_back(std::move(p));
  }
  std::ranges::sort(points);
  return static_cast<std::size_t>(std::unique(points.begin(), points.end()) - points.begin());
}

// P's values under each outer function: y, log y, exp y; nothing where one is undefined.
std::optional<Eigen::VectorXd> inner_values(const Rows& rows, const std::vector<std::size_t>& picked, Outer outer) {
  Eigen::VectorXd p(static_cast<Eigen::Index>(picked.size()));
  for (std::size_t i = 0; i < picked.size(); ++i) {
    const double y = rows.target[picked[i]];
    double& v = p[static_cast<Eigen::Index>(i)];
    switch (outer) {
      case Outer::none: v = y; break;
      case Outer::exp: v = y > 0 ? std::log(y) : NAN; break;
      case Outer::log: v = std::exp(y); break;
    }
    if (!std::isfinite(v)) return std::nullopt;
  }
  return p;
}

Eigen::MatrixXd monomial_columns(const Rows& rows, const std::vector<std::size_t>& picked,
                                 const std::vector<std::vector<int>>& exponents) {
  Eigen::MatrixXd A(static_cast<Eigen::Index>(picked.size()), static_cast<Eigen::Index>(exponents.size()));
  for (std::size_t i = 0; i < picked.size(); ++i)
    for (std::size_t t = 0; t < exponents.size(); ++t) {
      double m = 1;
      for (std::size_t v = 0; v < exponents[t].size(); ++v) m *= std::pow(rows.columns[v][picked[i]], exponents[t][v]);
      A(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(t)) = m;
    }
  return A;
}

// A's columns at `kept`.
Eigen::MatrixXd columns_at(const Eigen::MatrixXd& A, const std::vector<Eigen::Index>& kept) {
  Eigen::MatrixXd out(A.rows(), static_cast<Eigen::Index>(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) out.col(static_cast<Eigen::Index>(k)) = A.col(kept[k]);
  return out;
}

// The norm of each of A's columns (1 for a column of zeros): the scaling both solves divide by.
Eigen::VectorXd column_norms(const Eigen::MatrixXd& A) {
  return A.colwise().norm().transpose().unaryExpr([](double n) { return n > 0 ? n : 1.0; });
}

// The least-squares coefficients of b over A's columns (scaled to unit norm for the solve),
// where they fit b to rounding.
std::optional<Eigen::VectorXd> exact_fit(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  const double scale = b.norm();
  if (!(scale > 0) || !A.allFinite()) return std::nullopt;
  const Eigen::VectorXd norms = column_norms(A);
  const Eigen::VectorXd c =
      (A * norms.cwiseInverse().asDiagonal()).colPivHouseholderQr().solve(b).cwiseQuotient(norms);
  if (!c.allFinite() || !((A * c - b).norm() <= kExact * scale)) return std::nullopt;
  return c;
}

// The terms of an exact fit c that carry more than rounding, refitted without the others (all of
// them where the pruned polynomial no longer fits).
std::vector<Term> significant_terms(const Eigen::MatrixXd& A, const Eigen::VectorXd& b, const Eigen::VectorXd& c,
                                    const std::vector<std::vector<int>>& exponents) {
  std::vector<Eigen::Index> kept;
  for (Eigen::Index t = 0; t < c.size(); ++t)
    if (std::abs(c[t]) * A.col(t).norm() > kNegligible * b.norm()) kept.push_back(t);
  std::vector<Term> out;
  if (const auto pruned = kept.empty() ? std::nullopt : exact_fit(columns_at(A, kept), b)) {
    for (std::size_t k = 0; k < kept.size(); ++k)
      out.push_back({exponents[static_cast<std::size_t>(kept[k])], (*pruned)[static_cast<Eigen::Index>(k)]});
  } else {
    for (std::size_t t = 0; t < exponents.size(); ++t) out.push_back({exponents[t], c[static_cast<Eigen::Index>(t)]});
  }
  return out;
}

bool is_unit(double c) { return std::abs(c - 1) <= kUnit; }

// Σ (cᵢ/k)·mᵢ, the constant term last: a coefficient of 1 left out, one of −1 subtracted where −
// is an operator.
Genome sum_over(std::vector<Term> terms, double k, bool subtract) {
  std::ranges::stable_partition(terms, [](const Term& t) { return !is_constant(t); });
  Genome out;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const double c = terms[t].coefficient / k;
    const bool minus = t > 0 && subtract && is_unit(-c);
    if (is_unit(c) || minus) {
      if (is_constant(terms[t])) out.push_back(expr::exact_constant(1, 1, expr::Symbol::one));
      append_monomial(out, terms[t].exponents, false);
    } else {
      out.push_back(Node{Op::constant, 0, c});
      append_monomial(out, terms[t].exponents, true);
    }
    if (t > 0) out.push_back(Node{minus ? Op::sub : Op::add, 0, 0});
  }
  return out;
}

// Σ (cᵢ/k)·mᵢ as sum_over writes it, or with the monomial common to every term multiplied out
// of the sum where that is smaller: (x − 10)·y² for x·y² − 10·y².
Genome polynomial_written(const std::vector<Term>& terms, double k, bool subtract, const SizeWeights& weights) {
  Genome plain = sum_over(terms, k, subtract);
  if (terms.size() < 2) return plain;
  std::vector<int> common = terms.front().exponents;
  for (const Term& t : terms)
    for (std::size_t v = 0; v < common.size(); ++v) common[v] = std::min(common[v], t.exponents[v]);
  if (std::ranges::all_of(common, [](int e) { return e == 0; })) return plain;
  std::vector<Term> divided = terms;
  for (Term& t : divided)
    for (std::size_t v = 0; v < common.size(); ++v) t.exponents[v] -= common[v];
  Genome factored = sum_over(divided, k, subtract);
  append_monomial(factored, common, true);
  return weights.of(factored) < weights.of(plain) ? factored : plain;
}

// A polynomial P under its outer function, or the ratio P/Q.
struct Found {
  std::vector<Term> numerator, denominator;  // no denominator: outer(P)
  Outer outer = Outer::none;
};

// The formula with every coefficient divided by k: outer(k·(P/k)) (k = 1: outer(P)), or
// (P/k)/(Q/k).
Genome written(const Found& f, double k, bool subtract, const SizeWeights& weights) {
  Genome out;
  const auto append = [&out](const Genome& g) { out.insert(out.end(), g.begin(), g.end()); };
  if (!f.denominator.empty()) {
    append(polynomial_written(f.numerator, k, subtract, weights));
    append(polynomial_written(f.denominator, k, subtract, weights));
    out.push_back(Node{Op::div, 0, 0});
    return out;
  }
  if (k != 1) out.push_back(Node{Op::constant, 0, k});
  append(polynomial_written(f.numerator, k, subtract, weights));
  if (k != 1) out.push_back(Node{Op::mul, 0, 0});
  if (f.outer == Outer::exp) out.push_back(Node{Op::exp, 0, 0});
  if (f.outer == Outer::log) out.push_back(Node{Op::log, 0, 0});
  return out;
}

bool writes(const Genome& g, std::span<const Op> operators) {
  return std::ranges::all_of(g, [&](const Node& n) {
    return expr::arity(n.op) == 0 || std::ranges::find(operators, n.op) != operators.end();
  });
}

// The smallest writing by the operators: as found, or with every coefficient divided by one of
// them (the one that makes the most others ±1). A ratio's scale is arbitrary: only the latter.
std::optional<Genome> smallest_writing(const Found& f, std::span<const Op> operators, const SizeWeights& weights) {
  const bool subtract = std::ranges::find(operators, Op::sub) != operators.end();
  std::vector<double> scales;
  if (f.denominator.empty()) scales.push_back(1);
  for (const auto* terms : {&f.numerator, &f.denominator})
    for (const Term& t : *terms) scales.push_back(t.coefficient);
  // Smaller first, then with fewer constants that are not whole numbers: 30·x·z/((x − 10)·y²)
  // over x·z/((x/30 − 1/3)·y²).
  const auto rank = [&weights](const Genome& g) {
    return std::pair(weights.of(g), std::ranges::count_if(g, [](const Node& n) {
      return is_free_constant(n) && std::abs(n.value - std::round(n.value)) > kUnit * std::abs(n.value);
    }));
  };
  std::optional<Genome> best;
  for (double k : scales) {
    Genome g = written(f, k, subtract, weights);
    if (writes(g, operators) && (!best || rank(g) < rank(*best))) best = std::move(g);
  }
  return best;
}

// outer(P) for P of the lowest degree that fits outer⁻¹(y) to rounding.
std::optional<Found> polynomial_under(Outer outer, const Rows& rows, const std::vector<std::size_t>& picked,
                                      std::size_t most) {
  const auto b = inner_values(rows, picked, outer);
  if (!b) return std::nullopt;
  const auto variables = static_cast<std::uint32_t>(rows.columns.size());
  for (int degree = 1; monomial_count(degree, variables) <= most; ++degree) {
    const auto exponents = monomial_exponents(degree, variables);
    const Eigen::MatrixXd A = monomial_columns(rows, picked, exponents);
    if (const auto c = exact_fit(A, *b)) return Found{significant_terms(A, *b, *c, exponents), {}, outer};
  }
  return std::nullopt;
}

// The null vector of M, its largest coefficient ±1, where M has one to rounding and only one
// (the SVD of M with its columns scaled to unit norm: the smallest singular value within kExact
// of the largest, the next one not within kNegligible).
std::optional<Eigen::VectorXd> null_vector(const Eigen::MatrixXd& M) {
  if (!M.allFinite() || M.cols() < 2) return std::nullopt;
  const Eigen::VectorXd norms = column_norms(M);
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(M * norms.cwiseInverse().asDiagonal(), Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const Eigen::Index n = sigma.size();
  if (!(sigma[n - 1] <= kExact * sigma[0]) || sigma[n - 2] <= kNegligible * sigma[0]) return std::nullopt;
  Eigen::VectorXd v = svd.matrixV().col(n - 1).cwiseQuotient(norms);
  return v / v.cwiseAbs().maxCoeff();
}

// Whether P/Q, with P and Q the sums of the coefficients c times A's columns (P's the first
// `numerator_count`), fits y to rounding at the picked rows.
bool fits_ratio(const Rows& rows, const std::vector<std::size_t>& picked, const Eigen::MatrixXd& A,
                const Eigen::VectorXd& c, Eigen::Index numerator_count) {
  const Eigen::VectorXd p = A.leftCols(numerator_count) * c.head(numerator_count);
  const Eigen::VectorXd q = A.rightCols(A.cols() - numerator_count) * c.tail(A.cols() - numerator_count);
  double error = 0, scale = 0;
  for (Eigen::Index i = 0; i < p.size(); ++i) {
    const double y = rows.target[picked[static_cast<std::size_t>(i)]];
    error += (p[i] / q[i] - y) * (p[i] / q[i] - y);
    scale += y * y;
  }
  return error <= kExact * kExact * scale;
}

// P/Q over the monomials of P (degree dp) and Q (degree dq ≥ 1): y·Q − P = 0 on every row, so
// the coefficients are the null vector of [P's monomials | −y·Q's monomials]; then without the
// terms that carry only rounding, where the rest still fit. Q must have a term in a variable.
std::optional<Found> ratio_of_degrees(int dp, int dq, const Rows& rows, const std::vector<std::size_t>& picked) {
  const auto variables = static_cast<std::uint32_t>(rows.columns.size());
  std::vector<std::vector<int>> exponents = monomial_exponents(dp, variables);
  const auto numerator_count = static_cast<Eigen::Index>(exponents.size());
  for (auto& e : monomial_exponents(dq, variables)) exponents.push_back(std::move(e));
  const Eigen::MatrixXd A = monomial_columns(rows, picked, exponents);
  Eigen::MatrixXd M = A;
  for (Eigen::Index i = 0; i < M.rows(); ++i)
    M.row(i).tail(M.cols() - numerator_count) *= -rows.target[picked[static_cast<std::size_t>(i)]];
  const auto v = null_vector(M);
  if (!v || !fits_ratio(rows, picked, A, *v, numerator_count)) return std::nullopt;

  std::vector<Eigen::Index> kept;
  double largest = 0;
  for (Eigen::Index k = 0; k < v->size(); ++k) largest = std::max(largest, std::abs((*v)[k]) * M.col(k).norm());
  for (Eigen::Index k = 0; k < v->size(); ++k)
    if (std::abs((*v)[k]) * M.col(k).norm() > kNegligible * largest) kept.push_back(k);
  const auto kept_in_p = std::count_if(kept.begin(), kept.end(), [&](Eigen::Index k) { return k < numerator_count; });
  Eigen::VectorXd c = *v;
  std::vector<Eigen::Index> terms(static_cast<std::size_t>(v->size()));
  std::iota(terms.begin(), terms.end(), 0);
  if (kept.size() < terms.size() && kept_in_p > 0 && kept_in_p < static_cast<std::ptrdiff_t>(kept.size())) {
    const auto pruned = null_vector(columns_at(M, kept));
    if (pruned && fits_ratio(rows, picked, columns_at(A, kept), *pruned, kept_in_p)) c = *pruned, terms = kept;
  }
  Found f;
  for (std::size_t k = 0; k < terms.size(); ++k) {
    const auto index = static_cast<std::size_t>(terms[k]);
    const double coefficient = c[static_cast<Eigen::Index>(k)];
    if (coefficient == 0) continue;
    (terms[k] < numerator_count ? f.numerator : f.denominator).push_back({exponents[index], coefficient});
  }
  if (f.numerator.empty() || std::ranges::all_of(f.denominator, is_constant)) return std::nullopt;
  return f;
}

// P/Q for the pair of degrees (Q's at least 1) with the fewest coefficients that fits to rounding.
std::optional<Found> lowest_ratio(const Rows& rows, const std::vector<std::size_t>& picked, std::size_t most) {
  const auto variables = static_cast<std::uint32_t>(rows.columns.size());
  std::vector<std::pair<std::size_t, std::pair<int, int>>> pairs;  // (coefficients, (dp, dq))
  for (int dq = 1; dq <= kMostRatioDegree && monomial_count(dq, variables) < most; ++dq)
    for (int dp = 0; dp <= kMostRatioDegree && monomial_count(dp, variables) + monomial_count(dq, variables) <= most; ++dp)
      pairs.push_back({monomial_count(dp, variables) + monomial_count(dq, variables), {dp, dq}});
  std::ranges::sort(pairs);
  for (const auto& [count, degrees] : pairs)
    if (auto f = ratio_of_degrees(degrees.first, degrees.second, rows, picked)) return f;
  return std::nullopt;
}

}  // namespace

std::vector<Genome> transformed_polynomials(const Rows& rows, std::span<const Op> operators, const SizeWeights& weights) {
  const auto picked = picked_rows(rows.size());
  const std::size_t distinct = distinct_points(rows, picked);
  std::vector<Genome> out;
  const auto add = [&](const std::optional<Found>& f) {
    if (!f) return;
    if (auto g = smallest_writing(*f, operators, weights)) out.push_back(std::move(*g));
  };
  for (Outer outer : {Outer::none, Outer::exp, Outer::log})
    add(polynomial_under(outer, rows, picked, std::min(kMostMonomials, distinct / 2)));
  add(lowest_ratio(rows, picked, std::min(kMostRationalMonomials, distinct / 2)));
  return out;
}

}  // namespace specula::fit
