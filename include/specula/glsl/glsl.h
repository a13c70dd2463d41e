#pragma once
// GLSL for every specula model (the paper's Fig. 10, for all of docs/math.md §2): self-contained
// functions that compute, in float, what the C++ Model computes, with the exact normalization
// evaluated in the shader. Each emitted function's first line cites its source, as Filament's
// surface_brdf.fs does. The GLSL is in src/glsl/shaders/, compiled into the library (docs/glsl.md).
#include <array>
#include <cstddef>
#include <string>
#include <string_view>

#include "specula/models/model.h"

namespace specula::glsl {

/// The GLSL dialects specula emits: desktop GLSL 3.30 core, GLSL ES 3.00, and WebGL 2 (whose
/// shading language is GLSL ES 3.00; emitted identically, named for the user's benefit).
enum class Dialect { glsl330, gles300, webgl2 };
inline constexpr std::size_t kDialectCount = static_cast<std::size_t>(Dialect::webgl2) + 1;  // webgl2: the last

/// "glsl330", "gles300" or "webgl2"; throws InvalidArgument otherwise.
Dialect parse_dialect(std::string_view text);
const char* to_string(Dialect dialect) noexcept;

/// The first lines of a shader in `dialect`: "#version 330 core\n", or "#version 300 es\n" with
/// highp float and int precision.
std::string version_header(Dialect dialect);

/// GLSL (no #version, no uniforms; valid in every Dialect) defining the model's functions — its
/// lobe, its coefficient, its form's cosine, or the full BRDF — then
///     float specula_<id>(vec3 N, vec3 L, vec3 V, <its parameters as floats>)
///     float specula_brdf(vec3 N, vec3 L, vec3 V, vec4 params)
/// with params = the parameter values in ModelInfo::params order (x first). N, L and V are unit
/// vectors (L toward the light, V toward the viewer). The form and a coefficient that differs
/// from the model's own (Model::with_coef) are baked in. Lobe models return k·F(c) without testing
/// N·L, as Model does; full BRDFs return 0 below the horizon, as theirs do.
///
/// Accuracy: float arithmetic on the formulas of docs/math.md §2; the log lobe's coef(n) from
/// normalize::log_rv_approx's Chebyshev series (4e-7 relative for n ∈ (0, 1e30]); Schlick's k
/// by its closed form, or by a 24-term series in 1 − n where that form cancels (|1 − n| ≤ ½).
std::string model_glsl(const Model& model);

/// The languages model_source writes: GLSL, HLSL (Shader Model 4 and later), the Metal Shading
/// Language, and C++ (double; for exports, include/specula/exports/exports.h).
enum class Language { glsl, hlsl, msl, cpp };
inline constexpr std::size_t kLanguageCount = static_cast<std::size_t>(Language::cpp) + 1;  // cpp: the last

/// model_glsl's functions in `language`, rewritten word for word from the same GLSL (same names,
/// comments, arithmetic and normalization): HLSL and Metal in float, specula_brdf's vec4 a float4,
/// global constants `static const` (HLSL) and `constant` (Metal), Metal's built-ins as metal::NAME.
/// C++ in double: literals and the log lobe's series in double (its k within 1e-9 of the closed
/// form), formulas as expr::to_cpp prints them, every function inline, over the vector type Vec3
/// (and Vec2) and GLSL's built-ins that the text begins with (needs <cmath>; meant to go in a
/// namespace of the caller's); no specula_brdf, and lobe models return 0 below the horizon
/// (N.L <= 0 or N.V <= 0), as Model does. Language::glsl gives model_glsl(model).
std::string model_source(const Model& model, Language language);

/// The model's parameter values in the layout specula_brdf's `params` expects (unused: 0).
std::array<float, 4> model_params(const Model& model);

/// A parameter's name in the emitted code: its own for built-in models, p_NAME for user models
/// (so that no user name clashes with a keyword or built-in function).
std::string param_name(const ModelInfo& info, const ParamInfo& p);

/// Whether the model's GLSL has k as a literal — a coefficient given in place of the model's own
/// (Model::coef_overridden), or a user lobe's k by quadrature — rather than computing it from the
/// parameters: such a k holds at the model's parameter values only.
bool coef_is_baked(const Model& model);

/// "specula_<id>", every run of characters other than letters and digits as one "_": the name
/// of the model's own entry function.
std::string entry_name(const Model& model);

/// A float as a GLSL literal that reads back to the same float ("2.0", "0.197253996",
/// "2.02299907e-09"). InvalidArgument for a value no float holds (NaN, ±inf, beyond ±FLT_MAX).
std::string float_literal(double value);

/// A double as a C++ literal that reads back to the same double ("2.0", "0.19725399658349416").
std::string double_literal(double value);

}  // namespace specula::glsl
