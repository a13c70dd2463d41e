#pragma once
// The Gaussian family, F = exp(−n θ²/2), θ = acos c: c^n matched at the peak (docs/math.md §2
// `gauss`; the paper's Gauss BRDF, used with c = N·H). Every part of the family is stated here
// (families/family.h).
#include "specula/families/family.h"
#include "specula/lobes/gauss.h"

namespace specula::families {

inline constexpr ParamDefinition kGaussParams[] = {kExponent};

inline constexpr ModelDefinition kGaussModels[] = {
    {.id = "gauss", .name = "Gaussian lobe", .summary = "F = exp(−n θ²/2), θ = acos c",
     .source = "the paper's Gauss BRDF (used with c = N·H)", .form = Form::nh},
};

inline constexpr Family kGauss{
    .name = "gauss",
    .kind = ModelKind::lobe,
    .scalar = "include/specula/lobes/gauss.h, lobes::Gauss",
    .params = kGaussParams,
    .models = kGaussModels,
    // exact: Highway's Acos and Exp in double lanes. In double the exponent's rounding is
    // amplified by |ln F| (F = e^(ln F)), as in the scalar reference (lobes/gauss.h): 4 + 4·|ln F|
    // ulp. Float: 1 ulp, and F̃ = 0 below the flush point as power's.
    .bounds = {.exact_float = ulps(1, kFloatUlp, kFloatFlushed),
               .exact_double = {4 * kDoubleUlp, 4 * kDoubleUlp, 0, kDoubleMinNormal, kDoubleMinNormal},
               .fast_float = kFastTranscendental,
               .fast_double = kFastTranscendental},
    .sampling = sampling::Method::tabulated,
    .make_lobe = [](Values p) -> lobes::Lobe { return lobes::Gauss<double>{p[0]}; },
    .simd = simd::Family::gauss,  // GaussExact, GaussExactFloat, GaussFast
    .glsl = {"lobes/gauss.glsl", "specula_gauss_lobe", ""},
    .reference = {"lobes.csv", "lobe", "gauss"},
    .coefficients = {"normalization.csv", "lobe", "gauss"},
};

}  // namespace specula::families
