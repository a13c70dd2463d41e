#pragma once
// A Fresnel channel (brdf/fresnel.h) written as text, as the CLI's --fresnel and the walk's
// tables spell it (docs/fresnel.md, "Writing a channel"):
//   one                              F ≡ 1
//   schlick:f0=0.04[,f90=1][,p=5]    Schlick with any F90 and exponent
//   f82:f0=0.95,tint=0.9             F82-tint (Hoffman 2019)
//   dielectric:eta=1.5               the exact dielectric, η = n_transmitted / n_incident
//   conductor:eta=0.2,kappa=3.1      the exact conductor, η + iκ
// A name alone takes the defaults of its parameters (schlick: f0 = 0.04; f82: f0 = 0.04, tint = 1;
// dielectric: η = 1.5; conductor: η = 1.5, κ = 0).
#include <string>
#include <string_view>

#include "specula/brdf/fresnel.h"

namespace specula {

/// The channel `spec` writes. Throws InvalidArgument with one line naming the problem: an unknown
/// kind or parameter, a parameter given twice, a value that is not a number, or one outside the
/// channel's domain (analysis::fresnel_domain_error).
fresnel::Channel parse_fresnel(std::string_view spec);

/// The spec of `f` with every parameter of its kind: parse_fresnel(to_spec(f)) == f.
std::string to_spec(const fresnel::Channel& f);

}  // namespace specula
