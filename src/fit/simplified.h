#pragma once
// A fitted formula simplified inside the search (expr::simplify, docs/fit.md "Simplification"):
// the population and the front hold the simplified form wherever it computes the same on the
// training rows, so that an equal-error bloated form never occupies a size.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "constants.h"
#include "genome.h"

namespace specula::fit {

/// What a simplified formula may contain: the search's operators, plus subtraction and negation
/// (the signs simplify writes), and constants as the search's mode allows them.
struct SimplifyRules {
  std::vector<expr::Op> operators;
  Constants constants = Constants::fitted;
  SizeWeights weights;
  /// Per variable: positive on every row of the data, so the sign rules of expr::simplify hold.
  std::vector<bool> positive;
};

/// Per column: whether every value is > 0.
std::vector<bool> positive_columns(std::span<const std::span<const double>> columns);

/// Names v0, v1, … for the variables of a genome seen as an expr::Expression.
std::vector<std::string> slot_names(std::size_t count);

/// The most digits a sum may lose on every row: |a ± b| below 10⁻⁴·max(|a|, |b|) at each row.
inline constexpr double kCancelledDigits = 4;

/// Whether a sum or difference in `g` with a constant below it loses more than kCancelledDigits
/// of its operands' digits on every row (1573607.28 − 0.99999936^x · 1573606.29 for y near 1):
/// a fit by cancellation. sin(x) − x cancels near 0 only, and 1000 + x never.
bool relies_on_cancellation(const Genome& g, const Rows& rows);

/// `g` simplified where the simplified formula differs from g, evaluates within 1e-12 relative of
/// `predicted` (g's values) on every training row, is no larger by `rules.weights`, and is made of
/// what `rules` allows; otherwise nothing.
std::optional<Genome> simplified(const Genome& g, std::span<const double> predicted, const Rows& rows,
                                 const SimplifyRules& rules);

}  // namespace specula::fit
