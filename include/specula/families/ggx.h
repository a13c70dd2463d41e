#pragma once
// The GGX family: Trowbridge-Reitz D, Smith's height-correlated G, and one model per Fresnel kind
// (families/fresnel.h): Schlick's F0 (`ggx`), Schlick with F90 and exponent, F82-tint, the exact
// dielectric and the exact conductor (Walter et al. 2007; Heitz 2014; docs/math.md §2,
// docs/fresnel.md). Every part of the family is stated here (families/family.h).
#include "specula/brdf/ggx.h"
#include "specula/families/family.h"
#include "specula/families/fresnel.h"

namespace specula::families {

inline constexpr ParamDefinition kGgxAlpha{"alpha", 0.3, 1e-3, 1, false, "roughness"};
using GgxFresnel = FresnelParams<kGgxAlpha>;

inline constexpr ModelDefinition kGgxModels[] = {
    {.id = "ggx", .name = "GGX", .summary = "Trowbridge-Reitz D, Smith height-correlated G, Schlick F",
     .source = "Walter et al. 2007; Heitz 2014", .glsl_file = "brdfs/ggx.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Ggx{p[0], schlick_f0_channel(p)}; },
     .reference = {"brdfs.csv", "model", "ggx"}},
    {.id = "ggx-schlick", .name = "GGX (Schlick F0, F90, exponent)",
     .summary = "GGX with Schlick's F0 + (F90 - F0)(1 - V.H)^p", .source = "Walter et al. 2007; Schlick 1994",
     .params = GgxFresnel::schlick, .glsl_file = "brdfs/ggx-schlick.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Ggx{p[0], schlick_channel(p)}; },
     .reference = {"brdfs.csv", "model", "ggx-schlick"}},
    {.id = "ggx-f82", .name = "GGX (F82-tint)", .summary = "GGX with Hoffman's F82-tint Fresnel, as Cycles' metals",
     .source = "Walter et al. 2007; Hoffman 2019", .params = GgxFresnel::f82, .glsl_file = "brdfs/ggx-f82.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Ggx{p[0], f82_channel(p)}; },
     .reference = {"brdfs.csv", "model", "ggx-f82"}},
    {.id = "ggx-dielectric", .name = "GGX (dielectric)",
     .summary = "GGX reflection off a dielectric interface, exact Fresnel with total internal reflection",
     .source = "Walter et al. 2007; Cook & Torrance 1982 (Fresnel)", .params = GgxFresnel::dielectric,
     .glsl_file = "brdfs/ggx-dielectric.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Ggx{p[0], dielectric_channel(p)}; },
     .reference = {"brdfs.csv", "model", "ggx-dielectric"}},
    {.id = "ggx-conductor", .name = "GGX (conductor)", .summary = "GGX with the exact conductor Fresnel, index eta + i kappa",
     .source = "Walter et al. 2007; Born & Wolf (Fresnel)", .params = GgxFresnel::conductor,
     .glsl_file = "brdfs/ggx-conductor.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Ggx{p[0], conductor_channel(p)}; },
     .reference = {"brdfs.csv", "model", "ggx-conductor"}},
};

inline constexpr Family kGgx{
    .name = "ggx",
    .kind = ModelKind::brdf,
    .scalar = "include/specula/brdf/ggx.h, Ggx",
    .params = GgxFresnel::schlick_f0,
    .models = kGgxModels,
    // No transcendental function: both tiers are the scalar arithmetic (src/simd/brdf.cpp); the
    // Fresnel kinds other than Schlick's F0 are the scalar formula itself.
    .bounds = double_only(ulps(2, kDoubleUlp, 0), ulps(2, kDoubleUlp, 0)),
    .sampling = sampling::Method::ggx_visible_normals,
};

}  // namespace specula::families
