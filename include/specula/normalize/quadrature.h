#pragma once
// Numerical normalization of any lobe in either form (docs/math.md §3: integrate in a variable
// suited to narrow lobes). The integral runs over u = −ln c, split at u = w·4^j where w is
// the lobe's half-maximum width, with adaptive Gauss-Kronrod (31 points) on each piece:
//   rv: ρ₁(0) = 2π ∫₀^∞ F(u) e^(−2u) du           (truncated at u = 40: e^(−80) is below 1e-34)
//   nh: ρ₁(0) = 2π ∫₀^(ln2/2) F(u) (2e^(−2u) − 1) 4e^(−2u) du   (N·H = cos(θ_o/2))
// ρ₁(0) is the albedo at normal incidence with k = 1; the coefficient is 1/ρ₁(0).
#include "specula/lobes/lobes.h"

namespace specula::normalize {

struct Integral {
  double value = 0;
  double error_estimate = 0;  ///< sum of the pieces' Gauss-Kronrod error estimates
};

/// ρ₁(0) by quadrature: ≥ 13 significant digits for n ∈ [1e-3, 1e9].
Integral normal_incidence_albedo(const lobes::Lobe& lobe, Form form);

/// 1/ρ₁(0): the coefficient by quadrature.
double quadrature(const lobes::Lobe& lobe, Form form);

}  // namespace specula::normalize
