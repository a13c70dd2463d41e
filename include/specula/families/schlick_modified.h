#pragma once
// The second-degree Schlick family, F = (s c)²/(n − n c + s c)² (docs/math.md §2
// `schlick-modified`, reconstructed: the paper's "second degree" Schlick lobe, s = 1.25 there).
// Every part of the family is stated here (families/family.h).
#include "specula/families/family.h"
#include "specula/lobes/schlick.h"

namespace specula::families {

inline constexpr ParamDefinition kSchlickModifiedParams[] = {
    kExponent, {"s", 1.25, 0, 1e3, true, "the constant of Schlick's second-degree lobe (1.25 in the paper)"}};

inline constexpr ModelDefinition kSchlickModifiedModels[] = {
    {.id = "schlick-modified", .name = "Schlick, second degree", .summary = "F = (s c)²/(n − n c + s c)²",
     .source = "Schlick 1994, as cited by the paper (reconstructed, docs/math.md §2)", .form = Form::rv},
};

inline constexpr Family kSchlickModified{
    .name = "schlick-modified",
    .kind = ModelKind::lobe,
    .scalar = "include/specula/lobes/schlick.h, lobes::SchlickModified",
    .params = kSchlickModifiedParams,
    .models = kSchlickModifiedModels,
    // Rational: relative bounds where F ≥ the lane type's smallest normal number.
    .bounds = {.exact_float = ulps(5, kFloatUlp, kFloatMinNormal),
               .exact_double = ulps(6, kDoubleUlp, kDoubleMinNormal),
               .fast_float = ulps(6, kFloatUlp, kFloatMinNormal),
               .fast_double = ulps(6, kDoubleUlp, kDoubleMinNormal)},
    .sampling = sampling::Method::tabulated,
    .make_lobe = [](Values p) -> lobes::Lobe { return lobes::SchlickModified<double>{p[0], p[1]}; },
    .simd = simd::Family::schlick_modified,  // SchlickModified<D, fast>
    .glsl = {"lobes/schlick-modified.glsl", "specula_schlick_modified_lobe", ", s"},
    .reference = {"lobes.csv", "lobe", "schlick-modified"},
    .coefficients = {"normalization.csv", "lobe", "schlick-modified"},
};

}  // namespace specula::families
