#pragma once
// Fitting a shape's constants per parameter value: the target sampled where it lives (in
// u = −ln c scaled to its half-maximum width, and uniformly in c for the tails), constants fitted
// for the largest error (fit::fit_formula_constants, minimax) at the lowest parameter value from
// several starts, then carried up the grid, each fit starting from its neighbour's constants.
#include <cstdint>
#include <span>
#include <vector>

#include "shapes.h"
#include "specula/design/design.h"
#include "specula/lobes/lobes.h"

namespace specula::design {

/// The target at one parameter value, as the fits see it.
struct Samples {
  double param = 0;
  lobes::Lobe target;                  ///< a lobe target (unused for a function target)
  std::vector<std::vector<double>> x;  ///< rows: one column per per-pixel variable (c for a lobe)
  std::vector<double> value;           ///< the target at each row
};

/// e at each row of `columns` (its variables' values, one column each).
std::vector<double> evaluate_rows(const expr::Expression& e, const std::vector<std::vector<double>>& columns);

/// Parameter values over the range, between the grids' and beyond them, where a law (and a lobe
/// with laws) must be finite too.
inline constexpr std::size_t kDenseParams = 1025;

/// `count` parameter values over [lo, hi], log-spaced or even as log_spaced(lo, hi) says.
std::vector<double> param_grid(double lo, double hi, std::size_t count);

/// The rows the fits use at p: for max_rel only those where the target is ≥ zone.
Samples samples_at(const Settings& s, double p);
/// A function target's rows at p, every one: the tensor product of each per-pixel variable's
/// values over (0, 1] (86 even and 43 in t²/4 for one variable, 16 + 8 a side for two, 8 + 4 for
/// three; the output index of a target of several outputs is no such variable: it takes its
/// values 0, 1, …), the target evaluated there (non-finite values kept).
Samples function_rows(const Settings& s, double p);
/// The values of a target's output index: 0, 1, …, output_count − 1.
std::vector<double> output_axis(const Settings& s);

/// A shape's constants at each grid value, and the error each fit reached.
struct GridFit {
  std::vector<std::vector<double>> constants;  ///< [grid index][constant]
  std::vector<double> error;                   ///< the objective's error per grid value (inf: failed)
  double worst = INFINITY;                     ///< the largest of them

  bool ok() const { return std::isfinite(worst); }
};

/// Fits `shape` at every grid value. `fixed` (same length as the grid, or empty) gives the
/// values of the first fixed.size() constants at each grid value: those are held, the rest fitted.
/// A fit not finite somewhere on the rows, or a lobe negative there, counts as failed (inf).
/// `started`, if given, holds the fits of the grid's first values (as from the same call on a
/// prefix of the grid): they are kept, and the fits go on from the next value.
GridFit fit_over_grid(const Shape& shape, std::span<const Samples> grid, const Settings& s,
                      std::span<const std::vector<double>> fixed = {}, const GridFit* started = nullptr);

/// What a fitted shape computes, as text: its values on every 8th row of `rows`, to 6 significant
/// digits. Two shapes of the same signature compute the same function there (one family written
/// two ways, or two families that meet at their best fit): the search keeps the cheaper.
std::string value_signature(const Shape& shape, std::span<const double> constants, const Samples& rows, const Settings& s);

/// The objective's error of `shape` with `constants` on the rows (inf where not finite, or where a
/// lobe is negative).
double shape_error(const Shape& shape, std::span<const double> constants, const Samples& rows, const Settings& s);

/// The objective's largest error on every grid value's rows of `lobe`, an expression in the
/// per-pixel variables and then the range parameter (inf as shape_error).
double expression_grid_error(const expr::Expression& lobe, std::span<const Samples> grid, const Settings& s);

/// `lobe`'s plain constants (those of its laws) fitted together over the rows of every grid value
/// for the objective, from the values it has: the laws, each fitted alone, miss together what a
/// joint fit recovers. Returns the better of the two, with its grid error.
std::pair<expr::Expression, double> jointly_refitted(const expr::Expression& lobe, std::span<const Samples> grid,
                                                     const Settings& s);

}  // namespace specula::design
