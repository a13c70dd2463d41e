#pragma once
// A model for other tools (`specula export`, docs/exports.md): HLSL and Metal functions, a Disney
// BRDF Explorer .brdf file, and a C++ header that depends on nothing but <cmath>. All of them are
// written from the definitions the GLSL emitter uses (glsl::model_source): the same functions,
// the same arithmetic, the normalization computed from the parameters where the GLSL computes it.
#include <cstddef>
#include <string>
#include <string_view>

#include "specula/models/model.h"

namespace specula::exports {

enum class Format { hlsl, msl, brdf, cpp };
inline constexpr std::size_t kFormatCount = static_cast<std::size_t>(Format::cpp) + 1;  // cpp: the last

/// "hlsl", "msl", "brdf" or "cpp"; throws InvalidArgument otherwise.
Format parse_format(std::string_view text);
const char* to_string(Format format) noexcept;

/// The model in `format`, with a comment saying what it is and how to call it:
/// - hlsl, msl: the functions of glsl::model_glsl in that language (float), entry points
///   specula_<id>(N, L, V, params…) and specula_brdf(N, L, V, float4 params);
/// - brdf: a BRDF Explorer file: `analytic`, one slider `float NAME MIN MAX DEFAULT` per
///   parameter (slider_range; DEFAULT the model's value), and the GLSL with
///   `vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)`, 0 below the horizon as Model is;
/// - cpp: a header with namespace cpp_namespace(model) holding the functions in double and
///   `double f(const Vec3& N, const Vec3& L, const Vec3& V)`, the model at its parameters.
std::string export_model(const Model& model, Format format);

/// A slider of BRDF Explorer: [min, max] with min <= value <= max.
struct Slider {
  double min;
  double max;
};

/// The slider of a parameter at `value` (inside its range), from its default d: from 0 (50 d for
/// d < 0) to max(50 |d|, 1), cut to the range (a range that excludes its low end starts a
/// thousandth of the slider above it), widened to hold `value`. n (0, 1e9], d = 20: [1, 1000];
/// alpha [0.001, 1]: all of it; an inline parameter (any value, d = 1): [0, 50].
Slider slider_range(const ParamInfo& param, double value);

/// The C++ header's namespace: "specula_export_" and the model id with every run of other
/// characters than letters and digits as "_" (glsl::entry_name's spelling).
std::string cpp_namespace(const Model& model);

}  // namespace specula::exports
