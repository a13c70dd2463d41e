#pragma once
// Formulas read off the data by linear algebra (docs/fit.md, "Transformed polynomials"): where the
// target y, log y or exp y is a polynomial in the variables to rounding, or y a ratio of two, the
// formula is read off one least-squares solve (a null vector for the ratio) over the monomials.
// 8/(2 + x² + y²) is such a ratio; the search meets its 11 nodes only by chance.
#include <span>
#include <vector>

#include "constants.h"

namespace specula::fit {

/// The formulas P, exp(P) and log(P) for the polynomial P of lowest degree that fits y, log y or
/// exp y to 1e-9 of its scale on the rows (at most 512, evenly spaced), and the ratio P/Q of
/// polynomials (Q not constant) with the fewest coefficients that fits y so (the null vector of
/// y·Q − P over their monomials): less the terms that carry only rounding, each written in its
/// smallest scaling (every coefficient divided by one of them, coefficients ±1 bare) with a
/// monomial common to a sum's terms multiplied out where that is smaller. Only formulas the
/// operators write, and only with no more coefficients than 16 (32 for P/Q, each of degree ≤ 8) or half the
/// distinct points: never an interpolation. Data with noise give none.
std::vector<Genome> transformed_polynomials(const Rows& rows, std::span<const expr::Op> operators,
                                            const SizeWeights& weights);

}  // namespace specula::fit
