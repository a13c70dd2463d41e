#include "identify.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>

#include "specula/expr/simplify.h"

namespace specula::fit {
namespace {

using expr::Node;
using expr::Op;
using expr::Symbol;

using Matrix = std::vector<std::vector<double>>;

/// PSLQ's state: y = x·B (normalised), H lower trapezoidal (n × n−1); a zero of y is a column of B.
struct Pslq {
  int n;
  std::vector<double> y;
  Matrix H, B;

  explicit Pslq(std::span<const double> x) : n(static_cast<int>(x.size())), y(x.begin(), x.end()) {
    double norm = 0;
    for (double v : y) norm += v * v;
    norm = std::sqrt(norm);
    for (double& v : y) v /= norm;
    std::vector<double> s(static_cast<std::size_t>(n));
    double tail = 0;
    for (int j = n - 1; j >= 0; --j) s[at(j)] = std::sqrt(tail += y[at(j)] * y[at(j)]);
    H.assign(at(n), std::vector<double>(at(n - 1), 0.0));
    for (int j = 0; j < n - 1; ++j) {
      H[at(j)][at(j)] = s[at(j + 1)] / s[at(j)];
      for (int i = j + 1; i < n; ++i) H[at(i)][at(j)] = -y[at(i)] * y[at(j)] / (s[at(j)] * s[at(j + 1)]);
    }
    B = identity();
    for (int i = 1; i < n; ++i)
      for (int j = i - 1; j >= 0; --j) reduce(i, j);
  }

  static std::size_t at(int i) { return static_cast<std::size_t>(i); }
  Matrix identity() const {
    Matrix m(at(n), std::vector<double>(at(n), 0.0));
    for (int i = 0; i < n; ++i) m[at(i)][at(i)] = 1;
    return m;
  }

  /// Hermite reduction of H[i][j] by row j.
  void reduce(int i, int j) {
    const double t = std::round(H[at(i)][at(j)] / H[at(j)][at(j)]);
    if (t == 0) return;
    y[at(j)] += t * y[at(i)];
    for (int k = 0; k <= j; ++k) H[at(i)][at(k)] -= t * H[at(j)][at(k)];
    for (int k = 0; k < n; ++k) B[at(k)][at(j)] += t * B[at(k)][at(i)];
  }

  /// One iteration: swap the rows where γ^i·|H_ii| is largest, restore the corner, reduce.
  void iterate() {
    const double gamma = std::sqrt(4.0 / 3.0);
    int m = 0;
    double best = -1, power = 1;
    for (int i = 0; i < n - 1; ++i) {
      power *= gamma;
      if (power * std::abs(H[at(i)][at(i)]) > best) best = power * std::abs(H[at(i)][at(i)]), m = i;
    }
    std::swap(y[at(m)], y[at(m + 1)]);
    std::swap(H[at(m)], H[at(m + 1)]);
    for (auto& row : B) std::swap(row[at(m)], row[at(m + 1)]);
    if (m < n - 2) {
      const double t0 = std::hypot(H[at(m)][at(m)], H[at(m)][at(m + 1)]);
      const double t1 = H[at(m)][at(m)] / t0, t2 = H[at(m)][at(m + 1)] / t0;
      for (int i = m; i < n; ++i) {
        const double t3 = H[at(i)][at(m)], t4 = H[at(i)][at(m + 1)];
        H[at(i)][at(m)] = t1 * t3 + t2 * t4;
        H[at(i)][at(m + 1)] = -t2 * t3 + t1 * t4;
      }
    }
    for (int i = m + 1; i < n; ++i)
      for (int j = std::min(i - 1, m + 1); j >= 0; --j) reduce(i, j);
  }

  /// A lower bound on the norm of any relation (Ferguson–Bailey): 1 / max |H_jj|.
  double norm_bound() const {
    double largest = 0;
    for (int j = 0; j < n - 1; ++j) largest = std::max(largest, std::abs(H[at(j)][at(j)]));
    return largest > 0 ? 1 / largest : INFINITY;
  }
};

/// |a·x| / |x| below which a relation is taken: a fitted constant carries ~1e-10 of its own error.
constexpr double kRelationTolerance = 1e-9;
/// How near a closed form must come to the fitted value to be offered at all (relative).
constexpr double kIdentifyWindow = 1e-9;
/// Exponents and the root: |v|^d with d ≤ 4, each prime's and π's and e's exponent within ±6.
constexpr long long kLargestRoot = 4, kLargestExponent = 6;
constexpr std::array<int, 4> kPrimes = {2, 3, 5, 7};

bool fits_node(long long p, long long q) { return q >= 1 && q <= 255 && std::abs(p) <= 32767; }

Node exact(long long p, long long q, Symbol symbol = Symbol::one) {
  const long long common = std::gcd(p, q);
  return expr::exact_constant(static_cast<int>(p / common), static_cast<int>(q / common), symbol);
}

/// p/q = Π primes^(exponents), or nothing when it does not fit an exact constant.
std::optional<std::pair<long long, long long>> rational_of(std::span<const long long> exponents) {
  long long p = 1, q = 1;
  for (std::size_t k = 0; k < exponents.size(); ++k)
    for (long long e = 0; e < std::abs(exponents[k]); ++e) {
      (exponents[k] > 0 ? p : q) *= kPrimes[k];
      if (p > 32767 || q > 32767) return std::nullopt;
    }
  return std::make_pair(p, q);
}

/// value = sign · (p/q)^(1/d) · π^(g/d) · e^(h/d), written with as few nodes as the parts allow:
/// (2·π)^(−1/2) rather than 2^(−1/2)·π^(−1/2).
std::optional<Genome> product_of_powers(double sign, long long p, long long q, long long g, long long h, long long d) {
  Genome out;
  int factors = 0;
  const auto multiply = [&] { if (++factors > 1) out.push_back({Op::mul}); };
  const auto raise = [&](Node base, long long num, long long den) {
    out.push_back(base);
    if (num != den) out.push_back(exact(num, den)), out.push_back({Op::pow});
    multiply();
  };
  if (g == 1 || g == -1) {
    if (g == -1) std::swap(p, q);  // (p/q)^(1/d)·π^(−1/d) = ((q/p)·π)^(−1/d)
    if (!fits_node(p, q)) return std::nullopt;
    raise(exact(p, q, Symbol::pi), g, d);
  } else {
    if (p != q) {
      if (!fits_node(p, q)) return std::nullopt;
      raise(exact(p, q), 1, d);
    }
    if (g != 0) raise(exact(1, 1, Symbol::pi), g, d);
  }
  if (h != 0) {
    out.push_back(exact(h, d));
    out.push_back({Op::exp});
    multiply();
  }
  if (factors == 0) return std::nullopt;  // |v| = 1: an integer, snap_candidates' business
  if (sign < 0) out.push_back({Op::neg});
  return out;
}

/// A relation a over x (x[0] the unknown) with 0 < a[0] ≤ kLargestRoot, or nothing.
std::optional<std::vector<long long>> relation_of_first(std::span<const double> x) {
  auto relation = integer_relation(x, kLargestExponent, kRelationTolerance);
  if (!relation || (*relation)[0] == 0) return std::nullopt;
  if ((*relation)[0] < 0)
    for (long long& v : *relation) v = -v;
  if ((*relation)[0] > kLargestRoot) return std::nullopt;
  return relation;
}

/// |v|^d = 2^a·3^b·5^c·7^f·π^g·e^h.
std::optional<Genome> as_product_of_powers(double value) {
  const std::array<double, 7> x = {std::log(std::abs(value)), std::numbers::ln2, std::log(3.0), std::log(5.0),
                                   std::log(7.0), std::log(std::numbers::pi), 1.0};
  const auto relation = relation_of_first(x);
  if (!relation) return std::nullopt;
  const auto& a = *relation;
  // d·ln|v| + Σ a_k ln p_k + g ln π + h = 0:  |v|^d = Π p_k^(−a_k) · π^(−g) · e^(−h).
  const std::array<long long, 4> exponents = {-a[1], -a[2], -a[3], -a[4]};
  const auto rational = rational_of(exponents);
  if (!rational) return std::nullopt;
  return product_of_powers(value, rational->first, rational->second, -a[5], -a[6], a[0]);
}

/// d·v = ln(p/q).
std::optional<Genome> as_logarithm(double value) {
  const std::array<double, 5> x = {value, std::numbers::ln2, std::log(3.0), std::log(5.0), std::log(7.0)};
  const auto relation = relation_of_first(x);
  if (!relation) return std::nullopt;
  const auto& a = *relation;
  const std::array<long long, 4> exponents = {-a[1], -a[2], -a[3], -a[4]};
  auto rational = rational_of(exponents);
  if (!rational || !fits_node(rational->first, rational->second)) return std::nullopt;
  auto [p, q] = *rational;
  if (p == q) return std::nullopt;  // ln 1 = 0
  const bool negative = p < q;  // ln(2/3) = −ln(3/2)
  if (negative) std::swap(p, q);
  Genome out{exact(p, q), {Op::log}};
  if (a[0] > 1) out.push_back(exact(1, a[0])), out.push_back({Op::mul});
  if (negative) out.push_back({Op::neg});
  return out;
}

}  // namespace

std::optional<std::vector<long long>> integer_relation(std::span<const double> x, long long max_coefficient,
                                                       double tolerance) {
  if (x.size() < 2 || x.size() > 12) return std::nullopt;
  if (std::ranges::any_of(x, [](double v) { return !std::isfinite(v) || v == 0; })) return std::nullopt;
  Pslq pslq(x);
  const double bound = static_cast<double>(max_coefficient) * std::sqrt(static_cast<double>(x.size()));
  for (int iteration = 0; iteration < 100 * pslq.n; ++iteration) {
    for (int j = 0; j < pslq.n; ++j) {
      if (std::abs(pslq.y[Pslq::at(j)]) > tolerance) continue;
      std::vector<long long> relation;
      for (int k = 0; k < pslq.n; ++k) relation.push_back(std::llround(pslq.B[Pslq::at(k)][Pslq::at(j)]));
      if (std::ranges::any_of(relation, [&](long long v) { return std::abs(v) > max_coefficient; })) return std::nullopt;
      return relation;
    }
    if (pslq.norm_bound() > bound) return std::nullopt;  // any relation is larger than asked
    pslq.iterate();
  }
  return std::nullopt;
}

std::optional<expr::Node> exact_rational(double value) {
  constexpr long long kLargestNumerator = 32767, kLargestDenominator = 255;  // what a node holds
  if (!std::isfinite(value) || value == 0) return std::nullopt;
  // Continued-fraction convergents p/q of |value|, until one is within the window.
  long long p0 = 0, q0 = 1, p1 = 1, q1 = 0;
  double rest = std::abs(value);
  for (int term = 0; term < 40; ++term) {
    const double whole = std::floor(rest);
    if (whole > static_cast<double>(kLargestNumerator)) return std::nullopt;
    const long long a = static_cast<long long>(whole);
    const long long p = a * p1 + p0, q = a * q1 + q0;
    if (p > kLargestNumerator || q > kLargestDenominator) return std::nullopt;
    if (std::abs(static_cast<double>(p) / static_cast<double>(q) - std::abs(value)) <= kIdentifyWindow * std::abs(value))
      return expr::exact_constant(static_cast<int>(value < 0 ? -p : p), static_cast<int>(q), expr::Symbol::one);
    p0 = p1, q0 = q1, p1 = p, q1 = q;
    if (rest - whole <= 0) return std::nullopt;
    rest = 1 / (rest - whole);
  }
  return std::nullopt;
}

std::vector<Genome> elementary_constants(double value) {
  std::vector<Genome> out;
  if (!std::isfinite(value) || value == 0) return out;
  for (auto form : {as_product_of_powers(value), as_logarithm(value)}) {
    if (!form) continue;
    const expr::Expression simple = expr::simplify(expr::Expression(std::move(*form), {}));
    if (simple.nodes().size() < 2) continue;  // a lone exact constant: snap_candidates' business
    if (std::abs(expr::evaluate(simple, {}) - value) <= kIdentifyWindow * std::abs(value))
      out.emplace_back(simple.nodes().begin(), simple.nodes().end());
  }
  return out;
}

}  // namespace specula::fit
