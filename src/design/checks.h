#pragma once
// Every member normalized and checked, as `specula check` checks a model: k in closed form where
// closed_form.h derives one (and it agrees with quadrature), else by quadrature, at a few
// parameter values of the range, then energy conservation at every angle, reciprocity and
// non-negativity of the normalized lobe there.
#include <functional>
#include <string>

#include "specula/design/design.h"

namespace specula::design {

/// Sets `l.k` (k at timing_param), `l.k_formula` (k(p) in closed form, or empty) and `l.check`
/// ("pass", or the properties that fail and where), checking at check_params(s).
void normalize_and_check(Lobe& l, const Settings& s, const std::function<bool()>& stop);

}  // namespace specula::design
