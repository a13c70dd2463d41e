#pragma once
// The GGX family: Trowbridge-Reitz D, Smith's height-correlated G, Schlick's F (Walter et al.
// 2007; Heitz 2014; docs/math.md §2). Every part of the family is stated here (families/family.h).
#include "specula/brdf/ggx.h"
#include "specula/families/cook_torrance.h"
#include "specula/families/family.h"

namespace specula::families {

inline constexpr ParamDefinition kGgxParams[] = {{"alpha", 0.3, 1e-3, 1, false, "roughness"}, kF0};

inline constexpr ModelDefinition kGgxModels[] = {
    {.id = "ggx", .name = "GGX", .summary = "Trowbridge-Reitz D, Smith height-correlated G, Schlick F",
     .source = "Walter et al. 2007; Heitz 2014", .glsl_file = "brdfs/ggx.glsl",
     .make_brdf = [](Values p) -> FullBrdf { return Ggx{p[0], p[1]}; }, .reference = {"brdfs.csv", "model", "ggx"}},
};

inline constexpr Family kGgx{
    .name = "ggx",
    .kind = ModelKind::brdf,
    .scalar = "include/specula/brdf/ggx.h, Ggx",
    .params = kGgxParams,
    .models = kGgxModels,
    // No transcendental function: both tiers are the scalar arithmetic (src/simd/brdf.cpp).
    .bounds = double_only(ulps(2, kDoubleUlp, 0), ulps(2, kDoubleUlp, 0)),
    .sampling = sampling::Method::ggx_visible_normals,
};

}  // namespace specula::families
