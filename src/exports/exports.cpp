// specula export (include/specula/exports/exports.h): each format is glsl::model_source's text in
// its language with the comment, the entry and, for BRDF Explorer, the file's sections around it.
#include "specula/exports/exports.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <variant>

#include "sampler_cpp.h"
#include "specula/catalogue/model_meta.h"
#include "specula/exceptions.h"
#include "specula/expr/comment.h"
#include "specula/glsl/glsl.h"

namespace specula::exports {
namespace {

/// "model=ggx alpha=0.3 f0=1": the model and its parameters (model_meta), for a comment.
std::string model_line(const Model& model) {
  std::string line;
  for (const auto& [name, value] : model_meta(model)) line += fmt::format(" {}={}", name, value);
  return expr::comment_text(line.substr(1));
}

/// The model's parameter names as its GLSL spells them (p_NAME for a user's model).
std::vector<std::string> glsl_names(const Model& model) {
  std::vector<std::string> names;
  for (const auto& p : model.info().params) names.push_back(glsl::param_name(model.info(), p));
  return names;
}

std::string joined(const std::vector<std::string>& parts) {
  std::string text;
  for (const auto& part : parts) text += ", " + part;
  return text;
}

/// The note on k that the formats with live parameters (BRDF Explorer's sliders) need.
std::string coefficient_note(const Model& model) {
  if (glsl::coef_is_baked(model)) return fmt::format("k = {} baked in at the exported parameters", model.coef());
  if (!model.is_lobe()) return "a full BRDF, normalized by its formula";
  if (model.info().normalization == Normalization::none) return "k = 1";
  return "k computed in the shader from the parameters";
}

std::string float4_call(const Model& model, std::string_view type) {
  const auto p = glsl::model_params(model);
  return fmt::format("{}({}, {}, {}, {})", type, glsl::float_literal(p[0]), glsl::float_literal(p[1]),
                     glsl::float_literal(p[2]), glsl::float_literal(p[3]));
}

std::string shading_language(const Model& model, Format format) {
  const bool hlsl = format == Format::hlsl;
  return fmt::format(
      "// specula export --format {}: {}\n"
      "// {} functions: paste them into a shader.\n"
      "// N, L, V: unit vectors, L toward the light, V toward the viewer. At these parameters:\n"
      "//   float f = specula_brdf(N, L, V, {});\n{}",
      to_string(format), model_line(model),
      hlsl ? "HLSL (Shader Model 4 and later: FXC, DXC, Slang)"
           : "Metal Shading Language (built-ins as metal::NAME, no using directive needed)",
      float4_call(model, "float4"), glsl::model_source(model, hlsl ? glsl::Language::hlsl : glsl::Language::msl));
}

std::string number(double value) { return fmt::format("{}", value); }

std::string brdf_explorer(const Model& model) {
  const auto names = glsl_names(model);
  std::string sliders;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const Slider s = slider_range(model.info().params[i], model.params()[i]);
    sliders += fmt::format("float {} {} {} {}\n", names[i], number(s.min), number(s.max), number(model.params()[i]));
  }
  return fmt::format(
      "analytic\n\n"
      "# specula export --format brdf: {}\n"
      "# {}, for Disney's BRDF Explorer (github.com/wdas/brdf): one slider per parameter; {}.\n"
      "# [type] [name] [min val] [max val] [default val]\n\n"
      "::begin parameters\n{}::end parameters\n\n"
      "::begin shader\n{}"
      "// BRDF Explorer's entry: L toward the light, V toward the viewer, N the normal (X, Y unused:\n"
      "// the model is isotropic); 0 below the horizon, as specula's Model is.\n"
      "vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y) {{\n"
      "  if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) return vec3(0.0);\n"
      "  return vec3({}(N, L, V{}));\n}}\n"
      "::end shader\n",
      model_line(model), expr::comment_text(model.info().name), coefficient_note(model), sliders,
      glsl::model_glsl(model), glsl::entry_name(model), joined(names));
}

/// What holds at the exported parameters only, where something does: a baked k, an energy table.
std::string held_at_export(const Model& model) {
  if (model.compensated())
    return " (the energy table holds E at the exported parameters only)";
  if (glsl::coef_is_baked(model)) return " (k is baked in at the exported parameters)";
  return "";
}

std::string cpp_header(const Model& model) {
  std::vector<std::string> values;
  for (const double v : model.params()) values.push_back(glsl::double_literal(v));
  const std::string ns = cpp_namespace(model);
  const CppSampler sampler = cpp_sampler(model);
  return fmt::format(
      "// specula export --format cpp: {}\n"
      "// {}: the model in double, as specula's Model computes it, in a header that needs nothing but\n"
      "// <cmath>. N, L, V: unit vectors, L toward the light, V toward the viewer; 0 below the horizon.\n"
      "//   {}::f(N, L, V)   the model at these parameters\n"
      "//   {}::{}(N, L, V{})   at any{}\n"
      "//   {}::sample(wi, u1, u2), {}::pdf(wi, wo)   importance sampling, as specula's sampling::Sampler\n"
      "//     (N = +z, wi toward the light, wo toward the viewer; at these parameters)\n"
      "#pragma once\n#include <cmath>\n\nnamespace {} {{\n\n{}{}"
      "// The model at the exported parameters ({}).\n"
      "inline double f(const Vec3& N, const Vec3& L, const Vec3& V) {{ return {}(N, L, V{}); }}\n\n"
      "{}\n}}  // namespace {}\n",
      model_line(model), expr::comment_text(model.info().name), ns, ns, glsl::entry_name(model),
      joined(glsl_names(model)), held_at_export(model), ns, ns, ns, sampler.prelude,
      glsl::model_source(model, glsl::Language::cpp), model_line(model), glsl::entry_name(model), joined(values),
      sampler.body, ns);
}

}  // namespace

namespace {

// The formats' names, the one list parse_format and to_string read ("" outside the enum).
constexpr const char* name_of(Format format) noexcept {
  switch (format) {
    case Format::hlsl: return "hlsl";
    case Format::msl: return "msl";
    case Format::brdf: return "brdf";
    case Format::cpp: return "cpp";
  }
  return "";
}
static_assert(names_complete<Format, kFormatCount>(name_of));

}  // namespace

Format parse_format(std::string_view text) {
  if (const auto format = enum_named<Format, kFormatCount>(text, name_of)) return *format;
  throw InvalidArgument(fmt::format("unknown export format '{}' (expected {})", text,
                                    names_listed<Format, kFormatCount>(name_of)));
}

const char* to_string(Format format) noexcept { return name_of(format); }

std::string export_model(const Model& model, Format format) {
  switch (format) {
    case Format::hlsl:
    case Format::msl: return shading_language(model, format);
    case Format::brdf: return brdf_explorer(model);
    case Format::cpp: return cpp_header(model);
  }
  unreachable();
}

Slider slider_range(const ParamInfo& param, double value) {
  const double d = param.default_value;
  const double low = std::max(param.min, d < 0 ? 50 * d : 0.0);
  const double high = std::min(param.max, std::max(50 * std::abs(d), 1.0));
  const double start = param.min_exclusive && low == param.min ? low + (high - low) * 1e-3 : low;
  return {std::min(start, value), std::max(high, value)};
}

std::string cpp_namespace(const Model& model) {
  return "specula_export_" + glsl::entry_name(model).substr(std::string_view("specula_").size());
}

}  // namespace specula::exports
