#pragma once
// Averages of a Fresnel channel (brdf/fresnel.h): F_avg = 2∫₀¹ F(μ) μ dμ, the hemispherical
// reflectance of a Fresnel interface under uniform (cosine-weighted) light, which the energy
// compensations use (docs/fresnel.md).
#include <string>
#include <vector>

#include "specula/brdf/fresnel.h"

namespace specula::analysis {

struct FresnelAverage {
  double value = 0;
  double error = 0;      ///< the quadrature's error estimate (0 for a closed form)
  bool closed_form = false;
};

/// F_avg of one channel, to 1e-12 absolute or better (tested against mpmath at 40 digits,
/// tests/reference/fresnel.csv): the closed form for Schlick (any exponent) and for F82-tint where
/// its clamp is inactive; otherwise adaptive Gauss–Kronrod split at the channel's kinks (the
/// critical cosine of total internal reflection, the clamp's edges), with the ends smoothed where
/// F has a square-root edge. Throws InvalidArgument for parameters outside the channel's domain
/// (fresnel_domain_error).
FresnelAverage fresnel_average(const fresnel::Channel& f);

/// Why `f`'s parameters are outside its documented domain (empty when they are inside):
/// f0, f90 ∈ [0, 1], exponent ∈ [0.5, 50], tint ∈ [0, 1], η ∈ [1e-3, 1e3], κ ∈ [0, 1e3], all finite.
std::string fresnel_domain_error(const fresnel::Channel& f);

/// The cosines in (0, 1) where `f` has a kink: the critical cosine √(1 − η²) of a dielectric seen
/// from the denser side (η < 1), the edges of F82-tint's clamp to [0, 1].
std::vector<double> fresnel_kinks(const fresnel::Channel& f);

}  // namespace specula::analysis
