#pragma once
// The Lambert family, f = ρ/π (Lambert 1760): the diffuse reference. Every part of the family is
// stated here (families/family.h).
#include "specula/brdf/lambert.h"
#include "specula/families/family.h"

namespace specula::families {

inline constexpr ParamDefinition kLambertParams[] = {{"rho", 1, 0, 1, false, "diffuse albedo"}};

inline constexpr ModelDefinition kLambertModels[] = {
    {.id = "lambert", .name = "Lambert", .summary = "f = ρ/π", .source = "Lambert 1760",
     .glsl_file = "brdfs/lambert.glsl", .make_brdf = [](Values p) -> FullBrdf { return Lambert{p[0]}; },
     .reference = {"brdfs.csv", "model", "lambert"}},
};

inline constexpr Family kLambert{
    .name = "lambert",
    .kind = ModelKind::brdf,
    .scalar = "include/specula/brdf/lambert.h, Lambert",
    .params = kLambertParams,
    .models = kLambertModels,
    // No transcendental function: both tiers are the scalar arithmetic (src/simd/brdf.cpp).
    .bounds = double_only(ulps(2, kDoubleUlp, 0), ulps(2, kDoubleUlp, 0)),
    .sampling = sampling::Method::cosine,
};

}  // namespace specula::families
