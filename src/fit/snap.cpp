#include "snap.h"

#include "identify.h"
#include "simplified.h"

#include <cmath>
#include <limits>
#include <string>

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
/// then (in a formula that fits exactly) the elementary closed forms (identify.h).
std::vector<Genome> candidates(double value, Constants constants, bool fits_exactly) {
  std::vector<Genome> out;
  for (const Node& candidate : snap_candidates(value)) {
    if (constants == Constants::integer && candidate.denominator > 1) continue;
    if (candidate.symbol != Symbol::one && (constants == Constants::integer || !fits_exactly)) continue;
    out.push_back({candidate});
  }
  if (constants == Constants::fitted && fits_exactly)
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

Snapped snapped(const Genome& g, const Rows& rows, const SnapSettings& settings) {
  Snapped current = evaluated(g, rows, settings);
  if (settings.constants == Constants::none) return current;
  const double allowed = std::max(current.loss * (1 + settings.tolerance), settings.floor);
  // π, e, ln 2, √2 and √3 only in a formula that fits to rounding (or the target error): in a
  // rough one, 3·ln 2/2 for a constant near 1.04 claims a structure the data do not show.
  const bool fits_exactly = current.loss <= settings.floor;
  int refits_left = settings.max_refits;
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
