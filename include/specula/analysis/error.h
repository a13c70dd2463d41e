#pragma once
// How well one lobe approximates another (docs/math.md §3; the paper's Figs. 3 and 4): the maximum
// absolute error, where it occurs, and the maximum relative error inside the "epicenter" (where
// the reference is ≥ zone × its peak) and outside it (the attenuation zone, while the reference
// is > 0). Maxima are found exactly, not read off a grid: dense sampling in u = −ln c scaled to
// the reference's width (the variable in which every lobe is smooth and n-independent in shape),
// then golden-section refinement of the bracket around the best sample, to 1e-9 of the maximum.
#include "specula/lobes/lobes.h"

namespace specula::analysis {

struct ApproximationError {
  double max_abs = 0;
  double argmax_abs_deg = 0;       ///< the angle acos(c) where |F − F_ref| is largest
  double max_rel_epicenter = 0;    ///< max |F − F_ref| / F_ref where F_ref ≥ zone
  double max_rel_attenuation = 0;  ///< the same where 0 < F_ref < zone
};

/// `zone` ∈ (0, 1): the fraction of the reference's peak (F_ref(1) = 1) that bounds the epicenter.
ApproximationError approximation_error(const lobes::Lobe& model, const lobes::Lobe& reference,
                                       double zone = 0.5);

}  // namespace specula::analysis
