#pragma once
// Fitting a formula's numeric constants to data: weighted least squares, with the constants that
// enter linearly solved exactly (QR) and the rest by Levenberg–Marquardt on the projected
// problem (variable projection, Golub & Pereyra 1973; Kaufman's Jacobian).
#include <span>
#include <vector>

#include "genome.h"

namespace specula::fit {

/// Training rows: columns[v][r] is variable v in row r.
struct Rows {
  std::vector<std::span<const double>> columns;
  std::span<const double> target;
  std::vector<double> weights;  // per row; empty means 1
  std::size_t size() const { return target.size(); }
};

/// The most constants one formula may have.
inline constexpr std::size_t kMaxConstants = 64;

/// Values and derivatives with respect to every constant node (in node order):
/// value[r], gradient[k * rows + r].
void evaluate_with_gradient(std::span<const expr::Node> nodes, const Rows& rows,
                            std::vector<double>& value, std::vector<double>& gradient);

/// Which constant nodes (in node order) enter the formula linearly, chosen greedily so that the
/// formula is affine in all of them jointly.
std::vector<bool> linear_constants(std::span<const expr::Node> nodes);

/// Fits the constants of g in place, starting from their current values, and returns its
/// predictions for the rows (non-finite if the formula is undefined somewhere): in weighted least
/// squares, then, for max_abs and max_rel, for the largest error |f − y| (or |f − y|/|y|) itself:
/// Lawson's reweighted least squares and Chebyshev exchange steps on the linearized formula
/// (docs/fit.md). The constants kept are those of the lowest largest error seen; that refinement
/// replaces rows.weights by its own and does nothing where a max_rel target is 0. The other
/// metrics are fitted in least squares only. Integer mode rounds the fitted constants.
std::vector<double> fit_constants(Genome& g, const Rows& rows, Constants mode, Metric metric = Metric::rms);

}  // namespace specula::fit
