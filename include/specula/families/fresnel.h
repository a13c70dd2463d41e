#pragma once
// The Fresnel parameters of the microfacet models (brdf/fresnel.h; docs/fresnel.md): each kind's
// parameters as the registry states them, and the channel a model makes from its values. A
// microfacet family (ggx.h, beckmann.h) has one model per kind, named <family>-<kind>, whose
// parameters are the roughness followed by the kind's.
#include "specula/brdf/fresnel.h"
#include "specula/families/family.h"

namespace specula::families {

inline constexpr ParamDefinition kF0{"f0", 1, 0, 1, false, "Fresnel reflectance at normal incidence (1: F = 1)"};
inline constexpr ParamDefinition kF90{"f90", 1, 0, 1, false, "Schlick's reflectance at grazing incidence"};
inline constexpr ParamDefinition kSchlickPower{"exponent", 5, 0, 100, true, "Schlick's exponent p in (1 - c)^p"};
inline constexpr ParamDefinition kMetalF0{"f0", 0.9, 0, 1, false, "F82-tint's reflectance at normal incidence"};
inline constexpr ParamDefinition kTint{"tint", 0.9, 0, 1, false, "F82-tint: F near 82 degrees over Schlick's there"};
inline constexpr ParamDefinition kDielectricEta{"eta", 1.5, 1e-3, 1e3, false,
                                                "relative index n_below / n_above (< 1: from the denser side)"};
inline constexpr ParamDefinition kConductorEta{"eta", 0.2, 1e-3, 1e3, false, "real part of the complex index"};
inline constexpr ParamDefinition kKappa{"kappa", 3, 0, 1e3, false, "imaginary part (extinction) of the complex index"};

/// The channel of each kind from the values after the roughness (p[0] is the roughness).
inline fresnel::Channel schlick_f0_channel(Values p) { return {.kind = fresnel::Kind::schlick, .f0 = p[1]}; }
inline fresnel::Channel schlick_channel(Values p) {
  return {.kind = fresnel::Kind::schlick, .f0 = p[1], .f90 = p[2], .exponent = p[3]};
}
inline fresnel::Channel f82_channel(Values p) { return {.kind = fresnel::Kind::f82_tint, .f0 = p[1], .tint = p[2]}; }
inline fresnel::Channel dielectric_channel(Values p) { return {.kind = fresnel::Kind::dielectric, .eta = p[1]}; }
inline fresnel::Channel conductor_channel(Values p) {
  return {.kind = fresnel::Kind::conductor, .eta = p[1], .kappa = p[2]};
}

/// The parameters of a microfacet model with each kind, after its roughness `r`.
template <const ParamDefinition& r>
struct FresnelParams {
  static constexpr ParamDefinition schlick_f0[] = {r, kF0};
  static constexpr ParamDefinition schlick[] = {r, kF0, kF90, kSchlickPower};
  static constexpr ParamDefinition f82[] = {r, kMetalF0, kTint};
  static constexpr ParamDefinition dielectric[] = {r, kDielectricEta};
  static constexpr ParamDefinition conductor[] = {r, kConductorEta, kKappa};
};

}  // namespace specula::families
