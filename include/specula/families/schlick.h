#pragma once
// The Schlick family, F = c/(n − n c + c) (Schlick 1994; docs/math.md §2 `schlick`), with its
// bare and exactly normalized models. Every part of the family is stated here (families/family.h).
#include "specula/families/family.h"
#include "specula/lobes/schlick.h"
#include "specula/lobes/closed_form.h"

namespace specula::families {

inline constexpr ParamDefinition kSchlickParams[] = {kExponent};

inline constexpr ModelDefinition kSchlickModels[] = {
    {.id = "schlick", .name = "Schlick lobe", .summary = "F = c/(n − n c + c)", .source = "Schlick 1994",
     .form = Form::rv},
    {.id = "schlick-normalized", .name = "Normalized Schlick", .summary = "F = c/(n − n c + c), k exact for rv form",
     .source = "Schlick 1994; k from docs/math.md §2", .form = Form::rv, .normalization = Normalization::exact,
     .coef_text = "1/(2π[n² ln n/(n−1)³ − n/(n−1)² − 1/(2(n−1))])",
     .glsl_file = "coefficients/schlick-normalized.glsl"},
};

inline constexpr Family kSchlick{
    .name = "schlick",
    .kind = ModelKind::lobe,
    .scalar = "include/specula/lobes/schlick.h, lobes::Schlick",
    .params = kSchlickParams,
    .models = kSchlickModels,
    // Rational: relative bounds where F ≥ the lane type's smallest normal number. The fast float
    // tier takes a reciprocal and one Newton step; fast double divides.
    .bounds = {.exact_float = ulps(2, kFloatUlp, kFloatMinNormal),
               .exact_double = ulps(3, kDoubleUlp, kDoubleMinNormal),
               .fast_float = ulps(4, kFloatUlp, kFloatMinNormal),
               .fast_double = ulps(3, kDoubleUlp, kDoubleMinNormal)},
    .sampling = sampling::Method::tabulated,
    .make_lobe = [](Values p) -> lobes::Lobe { return lobes::Schlick<double>{p[0]}; },
    .simd = simd::Family::schlick,  // Schlick<D, fast>
    .glsl = {"lobes/schlick.glsl", "specula_schlick_lobe", ""},
    .closed_form = {.rv = lobes::schlick_rv},
    .reference = {"lobes.csv", "lobe", "schlick"},
    .coefficients = {"normalization.csv", "lobe", "schlick"},
};

}  // namespace specula::families
