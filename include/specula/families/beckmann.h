#pragma once
// The Beckmann family with Smith's masking: D = exp(−tan²δ/α²)/(π α² cos⁴δ), the height-correlated
// Smith G₂ (the random walk's Beckmann microsurface), and one model per Fresnel kind
// (families/fresnel.h), as GGX's (Walter et al. 2007; Heitz 2014; docs/math.md §2,
// docs/fresnel.md). Every part of the family is stated here (families/family.h).
#include "specula/brdf/beckmann.h"
#include "specula/families/family.h"
#include "specula/families/fresnel.h"

namespace specula::families {

inline constexpr ParamDefinition kBeckmannAlpha{"alpha", 0.3, 1e-3, 1, false, "roughness (RMS slope)"};
using BeckmannFresnel = FresnelParams<kBeckmannAlpha>;

inline constexpr ModelDefinition kBeckmannModels[] = {
    {.id = "beckmann", .name = "Beckmann (Smith G)", .summary = "Beckmann D, Smith height-correlated G, Schlick F",
     .source = "Walter et al. 2007; Heitz 2014", .glsl_file = "brdfs/beckmann.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Beckmann{p[0], schlick_f0_channel(p)}; },
     .reference = {"brdfs.csv", "model", "beckmann"}},
    {.id = "beckmann-schlick", .name = "Beckmann (Schlick F0, F90, exponent)",
     .summary = "Beckmann-Smith with Schlick's F0 + (F90 - F0)(1 - V.H)^p", .source = "Walter et al. 2007; Schlick 1994",
     .params = BeckmannFresnel::schlick, .glsl_file = "brdfs/beckmann-schlick.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Beckmann{p[0], schlick_channel(p)}; },
     .reference = {"brdfs.csv", "model", "beckmann-schlick"}},
    {.id = "beckmann-f82", .name = "Beckmann (F82-tint)", .summary = "Beckmann-Smith with Hoffman's F82-tint Fresnel",
     .source = "Walter et al. 2007; Hoffman 2019", .params = BeckmannFresnel::f82, .glsl_file = "brdfs/beckmann-f82.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Beckmann{p[0], f82_channel(p)}; },
     .reference = {"brdfs.csv", "model", "beckmann-f82"}},
    {.id = "beckmann-dielectric", .name = "Beckmann (dielectric)",
     .summary = "Beckmann-Smith reflection off a dielectric interface, exact Fresnel with total internal reflection",
     .source = "Walter et al. 2007; Cook & Torrance 1982 (Fresnel)", .params = BeckmannFresnel::dielectric,
     .glsl_file = "brdfs/beckmann-dielectric.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Beckmann{p[0], dielectric_channel(p)}; },
     .reference = {"brdfs.csv", "model", "beckmann-dielectric"}},
    {.id = "beckmann-conductor", .name = "Beckmann (conductor)",
     .summary = "Beckmann-Smith with the exact conductor Fresnel, index eta + i kappa",
     .source = "Walter et al. 2007; Born & Wolf (Fresnel)", .params = BeckmannFresnel::conductor,
     .glsl_file = "brdfs/beckmann-conductor.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Beckmann{p[0], conductor_channel(p)}; },
     .reference = {"brdfs.csv", "model", "beckmann-conductor"}},
};

inline constexpr Family kBeckmann{
    .name = "beckmann",
    .kind = ModelKind::brdf,
    .scalar = "include/specula/brdf/beckmann.h, Beckmann",
    .params = BeckmannFresnel::schlick_f0,
    .models = kBeckmannModels,
    // No kernel (Smith's Λ needs erfc): every tier is the scalar formula itself (src/simd/brdf.cpp),
    // exact; stated as 1 ulp, the least bound a family states.
    .bounds = double_only(ulps(1, kDoubleUlp, 0), ulps(1, kDoubleUlp, 0)),
    .sampling = sampling::Method::beckmann,
};

}  // namespace specula::families
