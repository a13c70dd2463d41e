#pragma once
// Directional albedo ρ(θ_i) = ∫_{H²} f(L, V) (N·V) dω_V (docs/math.md §1), by deterministic adaptive
// cubature that stays accurate for narrow lobes (n up to 1e4 and beyond, roughness down to 0.01),
// compact supports and grazing incidence: ≥ 8 significant digits where ρ ≥ 1e-3.
//   - lobes in `rv` form: one integral over the angle α from R; the azimuthal integral of N·V
//     around R is done in closed form, ∫₀^{2π} max(0, A + B cos φ) dφ, A = cos α cos θ_i,
//     B = sin α sin θ_i, and α runs in u = −ln cos α, split where the horizon starts cutting
//     (α = 90° − θ_i) and at the lobe's support end.
//   - lobes in `nh` form and full BRDFs: over the half vector H = (θ_h, φ_h), V = 2(L·H)H − L,
//     dω_V = 4 (L·H) dω_H; φ_h up to the closed-form horizon crossing, θ_h split at the lobe's
//     width and where the horizon starts and stops cutting.
#include <cstddef>
#include <span>
#include <vector>

#include "specula/models/model.h"

namespace specula::analysis {

struct Albedo {
  double value = 0;
  double error_estimate = 0;
  std::size_t evaluations = 0;  ///< of the BRDF or lobe by the cubature
};

/// ρ at the light's polar angle theta_i (radians, [0, π/2)).
Albedo albedo(const Model& model, double theta_i);

/// ρ at each angle (radians), in parallel; the result does not depend on the thread count.
std::vector<double> albedo_curve(const Model& model, std::span<const double> theta_i);

/// The lobe's or BRDF's angular width (radians): a scale for integrals and for sampling.
double angular_width(const Model& model);

/// Throws InvalidArgument unless 0 ≤ degrees < 90.
void require_incidence_deg(double degrees, const char* what = "theta");

}  // namespace specula::analysis
