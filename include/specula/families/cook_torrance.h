#pragma once
// The Cook-Torrance family, D F G over the cosines with Beckmann's D: the 1982 form (the paper's)
// and the normalized one (Walter et al. 2007) (docs/math.md §2). Every part of the family is
// stated here (families/family.h).
#include "specula/brdf/cook_torrance.h"
#include "specula/families/family.h"
#include "specula/families/fresnel.h"
#include "specula/families/ward.h"

namespace specula::families {

inline constexpr ParamDefinition kCookTorranceParams[] = {{"m", 0.3, 1e-3, 1, false, "RMS slope of the microfacets"},
                                                          kF0};

inline constexpr ModelDefinition kCookTorranceModels[] = {
    {.id = "cook-torrance-1982", .name = "Cook-Torrance (1982 form)",
     .summary = "D F G/(π (N·L)(N·V)), D = exp(−tan²δ/m²)/(m² cos⁴δ), dielectric F",
     .source = "Cook & Torrance 1982 (the paper's form)", .glsl_file = "brdfs/cook-torrance-1982.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return CookTorrance1982{p[0], p[1]}; },
     .reference = {"brdfs.csv", "model", "cook-torrance-1982"}},
    {.id = "cook-torrance", .name = "Cook-Torrance (normalized Beckmann)",
     .summary = "D F G/(4 (N·L)(N·V)), D = exp(−tan²δ/m²)/(π m² cos⁴δ), Schlick F", .source = "Walter et al. 2007",
     .glsl_file = "brdfs/cook-torrance.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return CookTorrance{p[0], p[1]}; },
     .reference = {"brdfs.csv", "model", "cook-torrance"}},
};

inline constexpr Family kCookTorrance{
    .name = "cook-torrance",
    .kind = ModelKind::brdf,
    .scalar = "include/specula/brdf/cook_torrance.h, CookTorrance1982 and CookTorrance",
    .params = kCookTorranceParams,
    .models = kCookTorranceModels,
    .bounds = kOneExponentialBounds,  // families/ward.h
    .sampling = sampling::Method::beckmann,
};

}  // namespace specula::families
