#pragma once
// A finished lobe's error over the whole domain: at each parameter value the exact maxima of
// `specula error` (analysis/error.h: dense sampling in u, golden-section refinement), over a dense
// grid of parameter values, then golden-section refinement in the parameter around the worst.
#include <functional>
#include <vector>

#include "specula/design/design.h"
#include "specula/lobes/lobes.h"
#include "specula/models/model.h"

namespace specula::design {

struct DomainError {
  double max_abs = 0, argmax_c = 1, argmax_param = 0;
  double max_rel = 0, argmax_rel_param = 0;  ///< in the epicenter (target ≥ zone)
  bool finite = true;  ///< false: the lobe is not finite at (argmax_c, argmax_param), and both errors are inf
};

/// Parameter values of the dense grid before refinement.
inline constexpr std::size_t kVerifyGrid = 97;

/// The points u = −ln c where the target and every lobe must be finite, at each parameter value
/// measured: 256 cosines even in (0, 1], 65 values of u over [0, 40] (denser near the peak), and
/// u = 745 (c = 5e-324, the smallest cosine the fits use).
const std::vector<double>& probe_log_cos();

/// The errors of lobe l against the target over the settings' range; where l is not finite at a
/// point of the probe at a parameter value measured, that point, and inf errors.
DomainError domain_error(const Lobe& l, const Settings& s, const std::function<bool()>& stop);

}  // namespace specula::design
