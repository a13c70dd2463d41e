#pragma once
// A certified upper bound on a function target's largest error (docs/designer.md, "A certified
// bound"): branch and bound over the box of the per-pixel variables and the range parameter with
// interval arithmetic (expr/interval.h) on F − T, where T is the target's formula.
#include <functional>

#include "specula/design/design.h"

namespace specula::design {

/// Each per-pixel variable is certified over [kCertifiedFloor, 1]; below it only the measured
/// points count (an interval reaching 0 holds x/x's 0/0).
inline constexpr double kCertifiedFloor = 1e-6;
/// Boxes examined per bound, at most.
inline constexpr std::size_t kMaxCertifyBoxes = 300'000;
/// The bound stops where it is within this (relative) of the largest error known.
inline constexpr double kCertifyTolerance = 0.02;

struct Certified {
  double bound = INFINITY;  ///< max |F − T| over the box is ≤ this (inf: not bounded within the budget)
  double found = 0;         ///< the largest |F − T| at a box's centre: a value the error reaches
  std::vector<double> where;  ///< that centre: the per-pixel variables, then the parameter (if any)
  std::size_t boxes = 0;
};

/// The bound for formula `formula` (a member's or an evaluable reference's) of a function target
/// with a formula (not a tabulated term), `known` an error it is known to reach (the measured
/// max_abs): boxes split in half along their widest side (relative to the domain's; in log scale
/// for a side spanning a factor of 4 or more) until the largest upper bound left is within
/// kCertifyTolerance (or 10⁻⁹) of the largest error known, or kMaxCertifyBoxes. The term itself
/// (the target's own formula) is bounded by 0.
Certified certify(const Settings& s, std::string_view formula, double known, const std::function<bool()>& stop);

/// Whether a target's members can be certified: a function target with a formula.
bool certifiable(const Settings& s);

}  // namespace specula::design
