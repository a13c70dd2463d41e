#pragma once
// The engines' own forms as shapes (docs/designer.md, "The engines' forms refitted"): each of a
// target's evaluable references with every number and every subexpression of the per-material
// parameter alone freed as a constant, so the designer fits them per parameter value, gives them
// laws and measures them as it does the shapes it enumerates — what the engine's form reaches with
// its constants chosen for the error, at the engine's cost.
#include <vector>

#include "shapes.h"
#include "specula/design/design.h"

namespace specula::design {

/// A reference's form as a shape: its key is "ID's form: " and the shape's text.
struct Seed {
  std::string reference;  ///< the reference's id
  Shape shape;
};

/// The forms of the settings' target's evaluable references other than the exact term, each with
/// its constants freed (their values at the range's low end as the fits' first start). An integer
/// written in the formula stays (an exponent, a factor 2); a form with more than kMaxSeedConstants
/// constants, or none, or of a cost model past Ranges::member_cost, is left out.
std::vector<Seed> reference_seeds(const Settings& s);

/// A form with more constants than this is not refitted (each fit's work grows with their square).
inline constexpr int kMaxSeedConstants = 12;

/// `form` with each constant that changes nothing the others cannot (its column of the Jacobian,
/// on 96 points spread over the per-pixel box (0, 1]^per_pixel, within 1e-5 relative of the span
/// of the columns before it: the 0.0425 of 1.04·(… + 0.0425) + 0.04) made an exact rational near
/// its value, which the fits hold: a direction that moves no error lets constants drift apart and
/// cancel at large magnitudes, which float arithmetic then loses.
Shape without_redundant_constants(Shape form, std::size_t per_pixel);

/// The form of `e` (an expression in the per-pixel variables, then the parameter if `has_param`)
/// with its parameter's subexpressions and its plain numbers freed, each at its value at `param`.
Shape freed_form(const expr::Expression& e, std::size_t per_pixel, double param);

}  // namespace specula::design
