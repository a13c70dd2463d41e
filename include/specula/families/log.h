#pragma once
// The logarithmic family, F_log = max(0, 1 − ½ log₂(1 − n log₂ c)) (Romanyuk et al. 2023;
// docs/math.md §2 `log`, §3, §4), with the bare lobe, the exact k and the paper's fitted k.
// Every part of the family is stated here (families/family.h).
#include "specula/families/family.h"
#include "specula/lobes/log.h"
#include "specula/lobes/closed_form.h"

namespace specula::families {

inline constexpr ParamDefinition kLogParams[] = {kExponent};

inline constexpr ModelDefinition kLogModels[] = {
    {.id = "log", .name = "Logarithmic lobe", .summary = "F = max(0, 1 − ½ log₂(1 − n log₂ c))",
     .source = "Romanyuk et al. 2023", .form = Form::rv},
    {.id = "log-normalized", .name = "Logarithmic lobe, exact normalization",
     .summary = "F_log with k = coef(n) in closed form (E₁)", .source = "Romanyuk et al. 2023; closed form docs/math.md §4",
     .form = Form::rv, .normalization = Normalization::exact,
     .coef_text = "1/(π(1 − e^a/(2 ln 2)(E₁(a) − E₁(4a)))), a = 2 ln 2/n",
     .glsl_file = "coefficients/log-normalized.glsl"},
    {.id = "log-paper", .name = "Logarithmic lobe, the paper's fitted k",
     .summary = "F_log with k = 0.197(n + 1.24) + 0.068/(0.64 + n)",
     .source = "Romanyuk et al. 2023 (TuringBot fit, as printed)", .form = Form::rv,
     .normalization = Normalization::formula, .coef_text = "0.197(n + 1.24) + 0.068/(0.64 + n)",
     .coef = [](double n) { return 0.197 * (n + 1.24) + 0.068 / (0.64 + n); },
     .glsl_file = "coefficients/log-paper.glsl"},
};

inline constexpr Family kLog{
    .name = "log",
    .kind = ModelKind::lobe,
    .scalar = "include/specula/lobes/log.h, lobes::Log",
    .params = kLogParams,
    .models = kLogModels,
    // exact: the t-space cases in double lanes (float arrays promoted); the absolute part is the
    // cancellation at the cut-off c₀ that the scalar lobe has too (4e-16, lobes/log.h). fast: "a
    // log of a log", one log₂ c to ~1 ulp, then log₂(1 + t) on t ∈ [0, 3] by a degree-5
    // polynomial, and for n ≥ 6 no exponent extraction at all (c > c₀ ≥ √½).
    .bounds = {.exact_float = {kFloatUlp, 0, 2e-14, 0, 0},
               .exact_double = {8 * kDoubleUlp, 0, 6e-16, 0, 0},
               .fast_float = kFastTranscendental,
               .fast_double = kFastTranscendental},
    .sampling = sampling::Method::log_t_space,
    .make_lobe = [](Values p) -> lobes::Lobe { return lobes::Log<double>{p[0]}; },
    .simd = simd::Family::log,  // LogExact, LogFast
    .glsl = {"lobes/log.glsl", "specula_log_lobe", ""},
    .closed_form = {.rv = lobes::log_rv},
    .reference = {"lobes.csv", "lobe", "log"},
    .coefficients = {"normalization.csv", "lobe", "log"},
};

}  // namespace specula::families
