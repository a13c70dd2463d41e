#pragma once
// A finished lobe's error over the whole domain: at each parameter value the exact maxima of
// `specula error` (analysis/error.h: dense sampling in u, golden-section refinement), over a dense
// grid of parameter values, then golden-section refinement in the parameter around the worst.
#include <functional>

#include "specula/design/design.h"
#include "specula/lobes/lobes.h"
#include "specula/models/model.h"

namespace specula::design {

struct DomainError {
  double max_abs = 0, argmax_c = 1, argmax_param = 0;
  double max_rel = 0, argmax_rel_param = 0;  ///< in the epicenter (target ≥ zone)
};

/// Parameter values of the dense grid before refinement.
inline constexpr std::size_t kVerifyGrid = 97;

/// The errors of lobe l against the target over the settings' range.
DomainError domain_error(const Lobe& l, const Settings& s, const std::function<bool()>& stop);

}  // namespace specula::design
