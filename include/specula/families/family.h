#pragma once
// What defines a built-in model family: the types of include/specula/families/<family>.h.
//
// A family is one scalar formula (a lobe, or a full BRDF) and the models built on it. Its header
// states every part of it in one place, and every consumer reads that header instead of a table
// of its own:
//
//   part                      field                  read by
//   scalar formula            scalar, make_lobe      src/catalogue/catalogue.cpp (Model), tests
//   models                    models, params         the registry (models(): ids, names, k)
//   normalization             closed_form, models[].normalization / coef
//                                                    the registry, normalize::closed_form
//   SIMD kernel               simd                   simd::eval_batch's dispatch (src/simd/lobes.cpp)
//   stated error bounds       bounds                 simd::error_bound, tests/simd
//   GLSL                      glsl, models[].glsl_file   glsl::model_glsl (CPU and GL renderers)
//   reference values          reference, models[].reference   tests/families (tests/reference/)
//   importance sampling       sampling               sampling::Sampler (src/sampling/sampler.cpp)
//
// families/families.h lists every family; tests/families checks that each registered built-in
// model has every part and that each part works.
#include <cstddef>
#include <span>
#include <string_view>

#include "specula/models/model.h"
#include "specula/models/sampling_method.h"
#include "specula/lobes/simd_bounds.h"

namespace specula::families {

using Values = std::span<const double>;

/// A parameter as the registry states it (ParamInfo, in literal form).
struct ParamDefinition {
  std::string_view name;
  double default_value;
  double min;  ///< valid range [min, max], or (min, max] when min_exclusive
  double max;
  bool min_exclusive;
  std::string_view meaning;
};

inline constexpr ParamDefinition kExponent{"n", 20, 0, 1e9, true, "specular exponent (sharpness of the lobe)"};

/// Where a family's or model's reference values live: the rows of tests/reference/<table> whose
/// `column` is `key` (made by the table's script, tests/reference/README.md).
struct ReferenceRows {
  std::string_view table;
  std::string_view column;
  std::string_view key;
};

/// A lobe model's k as a function of its exponent n (every normalized model's k depends on n alone).
using Coefficient = double (*)(double n);

/// One model of a family: what models() lists, and its own parts.
struct ModelDefinition {
  std::string_view id;
  std::string_view name;
  std::string_view summary;
  std::string_view source;  ///< where the formula comes from
  /// The model's own parameters where they differ from the family's (a Fresnel of its own kind:
  /// families/fresnel.h); empty: the family's.
  std::span<const ParamDefinition> params = {};
  Form form = Form::rv;     ///< lobe models: the default form
  /// Lobe models: none (k = 1), exact (k = the family's closed_form in `form`), or formula (`coef`).
  Normalization normalization = Normalization::none;
  std::string_view coef_text = "1";  ///< k as text
  Coefficient coef = nullptr;        ///< normalization = formula: k(n)
  /// Below src/glsl/shaders/: a lobe model's k(n) ("coefficients/<id>.glsl"; none where k = 1),
  /// a full BRDF's entry function specula_<id> ("brdfs/<id>.glsl").
  std::string_view glsl_file = "";
  FullBrdf (*make_brdf)(Values params) = nullptr;  ///< full BRDFs: the scalar model
  ReferenceRows reference = {};                    ///< full BRDFs: its values (lobes: the family's)
};

/// A lobe family's F(c) in GLSL: the file that defines it, the function's name, and the arguments
/// it takes after c and n (the model's further parameters, by their names).
struct LobeGlsl {
  std::string_view file;
  std::string_view function;
  std::string_view extra_args;  ///< e.g. ", s"
};

/// The error bound a family states for each tier and lane type (simd::ErrorBound's form, against
/// the scalar double formula). Full BRDFs are evaluated in double only: their float bounds repeat
/// the double ones.
struct StatedBounds {
  simd::ErrorBound exact_float, exact_double, fast_float, fast_double;

  constexpr const simd::ErrorBound& of(simd::Tier tier, bool single_precision) const noexcept {
    if (tier == simd::Tier::exact) return single_precision ? exact_float : exact_double;
    return single_precision ? fast_float : fast_double;
  }
};

// The constants the bounds are written in: ε (one ulp, relative), the smallest normal number, and
// where c^n and 2^(…) are flushed to 0 (2^(emin + 3): float 2⁻¹²⁵, double 2⁻¹⁰²¹).
inline constexpr double kFloatUlp = 0x1p-23, kDoubleUlp = 0x1p-52;
inline constexpr double kFloatMinNormal = 0x1p-126, kDoubleMinNormal = 0x1p-1022;
inline constexpr double kFloatFlushed = 0x1p-125, kDoubleFlushed = 0x1p-1021;

/// k ulp relative where F ≥ floor, |F̃ − F| ≤ floor below it.
constexpr simd::ErrorBound ulps(double k, double ulp, double floor) noexcept { return {k * ulp, 0, 0, floor, floor}; }

/// The fast tier of the transcendental lobes: 1e-4 relative where F ≥ 1e-3, 1e-7 absolute below.
inline constexpr simd::ErrorBound kFastTranscendental{1e-4, 0, 0, 1e-3, 1e-7};

/// Bounds of a family evaluated in double lanes only (full BRDFs).
constexpr StatedBounds double_only(simd::ErrorBound exact, simd::ErrorBound fast) noexcept {
  return {exact, exact, fast, fast};
}

/// The exact k of a lobe in each form, where a closed form is known (nullptr where not).
struct ClosedForms {
  Coefficient rv = nullptr;
  Coefficient nh = nullptr;

  constexpr Coefficient in(Form form) const noexcept { return form == Form::rv ? rv : nh; }
};

struct Family {
  std::string_view name;    ///< the file's name (families/<name>.h) and lobes' family_name
  ModelKind kind;
  std::string_view scalar;  ///< where the scalar formula is: its header and type
  std::span<const ParamDefinition> params;
  std::span<const ModelDefinition> models;
  StatedBounds bounds;
  /// How its models are importance-sampled; microfacet families take the roughness as their first
  /// parameter, lobe families the exponent n.
  sampling::Method sampling = sampling::Method::tabulated;
  // Lobe families only:
  lobes::Lobe (*make_lobe)(Values params) = nullptr;  ///< the scalar lobe at `params`
  /// The SIMD kernels' family: its kernels in src/simd/kernels-inl.h, chosen in src/simd/lobes.cpp.
  simd::Family simd = simd::Family::formula;
  LobeGlsl glsl = {};
  ClosedForms closed_form = {};
  ReferenceRows reference = {};       ///< F(c): tests/reference/lobes.csv
  ReferenceRows coefficients = {};    ///< k by quadrature: tests/reference/normalization.csv
};

/// The parameters of `model`: its own, or else its family's.
constexpr std::span<const ParamDefinition> params_of(const Family& family, const ModelDefinition& model) noexcept {
  return model.params.empty() ? family.params : model.params;
}

}  // namespace specula::families
