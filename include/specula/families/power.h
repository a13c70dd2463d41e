#pragma once
// The power family, F = cⁿ: Phong's lobe (rv form), Blinn's (nh form), and the six models built
// on it (docs/math.md §2 `phong`). Every part of the family is stated here (families/family.h).
#include <numbers>

#include "specula/families/family.h"
#include "specula/lobes/power.h"
#include "specula/lobes/closed_form.h"

namespace specula::families {

inline constexpr ParamDefinition kPowerParams[] = {kExponent};

inline constexpr ModelDefinition kPowerModels[] = {
    {.id = "phong", .name = "Phong lobe", .summary = "F = c^n", .source = "Phong 1975", .form = Form::rv},
    {.id = "phong-normalized", .name = "Normalized Phong", .summary = "F = c^n, k = (n+2)/(2π)",
     .source = "Lewis 1994; exact for rv form at normal incidence", .form = Form::rv,
     .normalization = Normalization::exact, .coef_text = "(n+2)/(2π)",
     .glsl_file = "coefficients/phong-normalized.glsl"},
    {.id = "phong-lafortune", .name = "Phong, Lafortune's normalization",
     .summary = "F = c^n, k = (n+1)/(2π) (no cos θ term: under-normalized)",
     .source = "Lafortune & Willems 1994; the paper's [6]", .form = Form::rv,
     .normalization = Normalization::formula, .coef_text = "(n+1)/(2π)",
     .coef = [](double n) { return (n + 1) / (2 * std::numbers::pi); },
     .glsl_file = "coefficients/phong-lafortune.glsl"},
    {.id = "blinn-phong", .name = "Blinn-Phong lobe", .summary = "F = (N·H)^n", .source = "Blinn 1977",
     .form = Form::nh},
    {.id = "blinn-phong-normalized", .name = "Normalized Blinn-Phong",
     .summary = "F = (N·H)^n, k = (n+2)(n+4)/(8π(2^(−n/2)+n))",
     .source = "Giesen 2009; exact for nh form at normal incidence", .form = Form::nh,
     .normalization = Normalization::exact, .coef_text = "(n+2)(n+4)/(8π(2^(−n/2)+n))",
     .glsl_file = "coefficients/blinn-phong-normalized.glsl"},
    {.id = "blinn-phong-approx", .name = "Blinn-Phong, (n+8)/(8π)",
     .summary = "F = (N·H)^n, k = (n+8)/(8π): the popular approximation, 2–8 % high",
     .source = "Akenine-Möller et al., Real-Time Rendering", .form = Form::nh,
     .normalization = Normalization::formula, .coef_text = "(n+8)/(8π)",
     .coef = [](double n) { return (n + 8) / (8 * std::numbers::pi); },
     .glsl_file = "coefficients/blinn-phong-approx.glsl"},
};

inline constexpr Family kPower{
    .name = "power",
    .kind = ModelKind::lobe,
    .scalar = "include/specula/lobes/power.h, lobes::Power",
    .params = kPowerParams,
    .models = kPowerModels,
    // exact: c^n = 2^(n log₂ c), log₂ c as a double-double in double lanes; float arrays take
    // log₂ F in double (~1e-11) and 2^(…) in float lanes, rounded once. F̃ = 0 below the flush
    // point, so |F̃ − F| ≤ that there. fast: short polynomials in the lane type.
    .bounds = {.exact_float = ulps(1, kFloatUlp, kFloatFlushed),
               .exact_double = ulps(2, kDoubleUlp, kDoubleFlushed),
               .fast_float = kFastTranscendental,
               .fast_double = kFastTranscendental},
    .sampling = sampling::Method::power_cosine,
    .make_lobe = [](Values p) -> lobes::Lobe { return lobes::Power<double>{p[0]}; },
    .simd = simd::Family::power,  // PowerExact, PowerExactFloat, PowerFast
    .glsl = {"lobes/power.glsl", "specula_power_lobe", ""},
    .closed_form = {lobes::phong_rv, lobes::blinn_phong_nh},
    .reference = {"lobes.csv", "lobe", "power"},
    .coefficients = {"normalization.csv", "lobe", "power"},
};

}  // namespace specula::families
