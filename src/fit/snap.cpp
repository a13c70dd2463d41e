#include "snap.h"

#include "identify.h"
#include "simplified.h"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <ranges>
#include <span>
#include <string>
#include <utility>

namespace specula::fit {
namespace {

using expr::Node;
using expr::Op;
using expr::Symbol;

constexpr int kLargestDenominator = 12;
/// Simple numbers only: integers up to 1000, fractions p/q with |p| ≤ 100, symbols' multiples with
/// |p| ≤ 12 (1737/2 or 123·ln 2 is no simpler than the double it would replace).
constexpr int kLargestInteger = 1000, kLargestFractionNumerator = 100, kLargestSymbolNumerator = 12;
/// A symbol's simple multiples: p·π/q for these q. With every q ≤ 12 the five symbols' multiples
/// lie about 0.005 apart near 1, so that some one fits nearly any constant of a rough formula
/// (6·e/11 for 1.4828): numerology, not a clean constant.
constexpr int kSymbolDenominators[] = {1, 2, 3, 4, 6};
/// How far from the fitted value a candidate may be: the loss decides, this only bounds the tries.
constexpr double kWindow = 0.02;

void add_candidate(std::vector<Node>& out, double value, int denominator, Symbol symbol) {
  const double unit = expr::symbol_value(symbol) / denominator;
  const double numerator = std::round(value / unit);
  const int largest = symbol != Symbol::one ? kLargestSymbolNumerator
                      : denominator == 1    ? kLargestInteger
                                            : kLargestFractionNumerator;
  if (numerator == 0 || std::abs(numerator) > largest) return;
  const Node candidate = expr::exact_constant(int(numerator), denominator, symbol);
  if (std::abs(candidate.value - value) > kWindow * std::abs(value)) return;
  for (const Node& seen : out)
    if (seen.value == candidate.value) return;  // 2/4 is 1/2, already tried
  out.push_back(candidate);
}

/// What a constant of `value` is tried as, simplest first: snap_candidates() as the mode allows,
/// then (in a formula that fits exactly) a rational with a larger denominator and the elementary
/// closed forms (identify.h).
std::vector<Genome> candidates(double value, Constants constants, bool fits_exactly) {
  std::vector<Genome> out;
  for (const Node& candidate : snap_candidates(value)) {
    if (constants == Constants::integer && candidate.denominator > 1) continue;
    if (candidate.symbol != Symbol::one && (constants == Constants::integer || !fits_exactly)) continue;
    out.push_back({candidate});
  }
  if (constants != Constants::fitted || !fits_exactly) return out;
  // A short decimal (q dividing 1000: 1.05, not 21/20) reads better as the number it is.
  const auto rational = exact_rational(value);
  if (rational && 1000 % rational->denominator != 0 &&
      std::ranges::none_of(out, [&](const Genome& c) { return c.front().value == rational->value; }))
    out.push_back({*rational});
  for (Genome& form : elementary_constants(value)) out.push_back(std::move(form));
  return out;
}

}  // namespace

std::vector<Node> snap_candidates(double value) {
  std::vector<Node> out{expr::exact_constant(0, 1, Symbol::one)};
  if (!std::isfinite(value)) return out;
  for (int q = 1; q <= kLargestDenominator; ++q) add_candidate(out, value, q, Symbol::one);
  for (std::size_t s = 1; s < expr::kSymbolCount; ++s)
    for (int q : kSymbolDenominators) add_candidate(out, value, q, static_cast<Symbol>(s));
  return out;
}

Snapped refitted(Genome g, const Rows& rows, const SnapSettings& settings) {
  const std::vector<double> predicted = fit_constants(g, rows, settings.constants, settings.metric);  // exact ones held
  double loss = to_loss(settings.metric, measure(settings.metric, predicted, rows.target));
  if (std::isnan(loss)) loss = std::numeric_limits<double>::infinity();
  return {std::move(g), loss};
}

/// The loss of `g` as it is, constants unchanged.
Snapped evaluated(const Genome& g, const Rows& rows, const SnapSettings& settings) {
  std::vector<double> predicted(rows.size());
  expr::evaluate_batch(expr::Expression(g, slot_names(rows.columns.size())), rows.columns, predicted);
  double loss = to_loss(settings.metric, measure(settings.metric, predicted, rows.target));
  if (std::isnan(loss)) loss = std::numeric_limits<double>::infinity();
  return {g, loss};
}

namespace {

/// How far the free constants of `g` are from simple: how many no simple number matches to 10⁻⁹
/// (relative), then how many no integer does — the digits and fractions a reader must take in.
std::pair<int, int> unsimple_constants(const Genome& g) {
  const auto matches = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); };
  int unmatched = 0, fractions = 0;
  for (const Node& n : g) {
    if (!is_free_constant(n)) continue;
    const auto near = snap_candidates(n.value);
    unmatched += std::ranges::none_of(near, [&](const Node& c) { return matches(c.value, n.value); });
    fractions += !matches(std::round(n.value), n.value);
  }
  return {unmatched, fractions};
}

/// Whether constant j moves on the free path of `rates` (free_scale_rates): at least 0.1 of the
/// fastest one's rate.
bool on_free_path(std::span<const double> rates, std::size_t j) {
  const double largest = std::abs(std::ranges::max(rates, {}, [](double r) { return std::abs(r); }));
  return std::abs(rates[j]) >= 0.1 * largest;
}

/// The relative rates d(ln c_j)/dt of a path along which g's free constants move together and no
/// value on the rows changes (a·x/(b·x − c) keeps its values for (k·a, k·b, k·c): rates 1, 1, 1): the
/// null vector of the Jacobian by the constants' logs, over the constants that matter (a column
/// above 10⁻⁸ of the largest; a negligible or zero constant has rate 0: it is no scale, snapping
/// to 0 is its business). Nothing where every direction changes the values (the smallest singular
/// value above 10⁻⁸ of the largest) or the path moves fewer than two constants.
std::optional<std::vector<double>> free_scale_rates(const Genome& g, const Rows& rows) {
  std::vector<double> value, gradient, constants;
  evaluate_with_gradient(g, rows, value, gradient);
  for (const Node& n : g)
    if (is_free_constant(n)) constants.push_back(n.value);
  const auto n = static_cast<Eigen::Index>(rows.size());
  if (constants.size() < 2 || n == 0) return std::nullopt;
  Eigen::MatrixXd J(n, static_cast<Eigen::Index>(constants.size()));
  for (std::size_t j = 0; j < constants.size(); ++j)
    for (Eigen::Index r = 0; r < n; ++r)
      J(r, static_cast<Eigen::Index>(j)) = gradient[j * rows.size() + static_cast<std::size_t>(r)] * constants[j];
  if (!J.allFinite()) return std::nullopt;
  const Eigen::VectorXd norms = J.colwise().norm();
  std::vector<Eigen::Index> matter;
  for (Eigen::Index j = 0; j < norms.size(); ++j)
    if (norms(j) > 1e-8 * norms.maxCoeff()) matter.push_back(j);
  if (matter.size() < 2) return std::nullopt;
  Eigen::MatrixXd M(n, static_cast<Eigen::Index>(matter.size()));
  for (std::size_t k = 0; k < matter.size(); ++k) M.col(static_cast<Eigen::Index>(k)) = J.col(matter[k]);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const Eigen::Index last = sigma.size() - 1;
  if (sigma(last) > 1e-8 * sigma(0)) return std::nullopt;
  std::vector<double> rates(constants.size(), 0.0);
  for (std::size_t k = 0; k < matter.size(); ++k)
    rates[static_cast<std::size_t>(matter[k])] = svd.matrixV()(static_cast<Eigen::Index>(k), last);
  if (std::ranges::count_if(std::views::iota(std::size_t{0}, rates.size()), [&](std::size_t j) { return on_free_path(rates, j); }) < 2)
    return std::nullopt;
  return rates;
}

/// `g` moved along the free path (rates, above) until its free constant number `held` is ±1, that
/// one then exact: c_j·|c_held|^(−rate_j / rate_held).
Genome moved_to_unit(const Genome& g, std::size_t held, std::span<const double> rates) {
  Genome out = g;
  std::size_t k = 0, held_node = 0;
  double held_value = 0;
  for (std::size_t i = 0; i < out.size(); ++i)
    if (is_free_constant(out[i]) && k++ == held) held_node = i, held_value = out[i].value;
  k = 0;
  for (Node& n : out)
    if (is_free_constant(n)) n.value *= std::pow(std::abs(held_value), -rates[k++] / rates[held]);
  out[held_node] = expr::exact_constant(held_value < 0 ? -1 : 1, 1, Symbol::one);
  return out;
}

/// `current` with a constant the others make up for held at ±1: a fit leaves a free scale wherever
/// it drifted (−1.3e11·z/(4.3e10/x − 4.3e9) for −30·z/(10/x − 1)). Each constant on the free path
/// is tried, moved there along it and the others refitted; of those within the loss allowed, the
/// one that leaves the most others at simple numbers, then at integers. Nothing when there is no
/// free path.
std::optional<Snapped> without_free_scale(const Snapped& current, const Rows& rows, const SnapSettings& settings,
                                          double allowed, int& refits_left) {
  const auto rates = free_scale_rates(current.genome, rows);
  if (!rates) return std::nullopt;
  std::optional<Snapped> best;
  std::pair<int, int> best_unsimple;
  for (std::size_t held = 0; held < rates->size(); ++held) {
    if (!on_free_path(*rates, held)) continue;
    if (--refits_left < 0 || settings.stop()) break;
    Snapped tried = refitted(moved_to_unit(current.genome, held, *rates), rows, settings);
    if (tried.loss > allowed || !settings.acceptable(tried.genome)) continue;
    const auto unsimple = unsimple_constants(tried.genome);
    if (!best || unsimple < best_unsimple) {
      best = std::move(tried);
      best_unsimple = unsimple;
    }
  }
  return best;
}

}  // namespace

Snapped snapped(const Genome& g, const Rows& rows, const SnapSettings& settings) {
  Snapped current = evaluated(g, rows, settings);
  if (settings.constants == Constants::none) return current;
  const double allowed = std::max(current.loss * (1 + settings.tolerance), settings.floor);
  // π, e, ln 2, √2 and √3 only in a formula that fits to rounding (or the target error): in a
  // rough one, 3·ln 2/2 for a constant near 1.04 claims a structure the data do not show.
  const bool fits_exactly = current.loss <= settings.floor;
  int refits_left = settings.max_refits;
  if (auto held = without_free_scale(current, rows, settings, allowed, refits_left)) current = std::move(*held);
  for (std::size_t i = 0; i < current.genome.size() && refits_left > 0; ++i) {
    if (current.genome[i].op != Op::constant || expr::is_exact(current.genome[i])) continue;
    for (const Genome& candidate : candidates(current.genome[i].value, settings.constants, fits_exactly)) {
      if (--refits_left < 0 || settings.stop()) return current;
      Snapped tried = refitted(replaced(current.genome, i, i, candidate), rows, settings);
      if (tried.loss <= allowed && settings.acceptable(tried.genome)) {
        current = std::move(tried);
        break;
      }
    }
  }
  return current;
}

}  // namespace specula::fit
