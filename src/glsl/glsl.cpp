#include "specula/glsl/glsl.h"

#include <cctype>
#include <cfloat>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <span>
#include <stdexcept>
#include <vector>

#include "dialect.h"
#include "formula_glsl.h"
#include "specula/exceptions.h"
#include "specula/expr/comment.h"
#include "specula/families/families.h"
#include "specula/normalize/log_coef_float.h"
#include "src/glsl/shader_files.h"

namespace specula::glsl {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kLn2 = std::numbers::ln2;

/// What differs between the languages before translate(): the precision of literals (float in the
/// shading languages, double in C++), the printer of formulas, and the horizon test of C++'s lobes.
struct Target {
  Language language;

  bool in_double() const noexcept { return language == Language::cpp; }
  std::string literal(double value) const { return in_double() ? double_literal(value) : float_literal(value); }
  FormulaPrinter printer() const noexcept { return in_double() ? expr::to_cpp : expr::to_glsl; }
};

/// Clenshaw's recurrence for a series of normalize::log_coef_chebyshev, unrolled.
std::string chebyshev_function(const Target& target, const std::string& name, std::span<const double> c,
                               double high) {
  const auto lit = [&](double value) { return target.literal(value); };
  std::string body = fmt::format(
      "// Clenshaw's recurrence for sum_k c_k T_k(t), t = 2x/{} - 1 (series by scripts/make_log_coef_fit.py).\n"
      "float {}(float x) {{\n  float t = 2.0 * x / {} - 1.0;\n  float b1 = 0.0, b2 = 0.0, b0;\n",
      lit(high), name, lit(high));
  for (std::size_t k = c.size() - 1; k >= 1; --k)
    body += fmt::format("  b0 = {} + 2.0 * t * b1 - b2; b2 = b1; b1 = b0;\n", lit(c[k]));
  body += fmt::format("  return {} + t * b1 - b2;\n}}", lit(c[0]));
  return body;
}

/// `float specula_erfc(float x)` for x ≥ 0: the C library's in double targets (C++), else
/// Numerical Recipes' erfcc (Press et al. 1992, §6.2), relative error below 1.2e-7 (float's rounding).
std::string erfc_function(const Target& target) {
  if (target.in_double()) return "// erfc(x), the C library's.\nfloat specula_erfc(float x) {\n  return erfc(x);\n}";
  return "// Numerical Recipes' erfcc (Press et al. 1992, 6.2) for x >= 0: relative error below 1.2e-7.\n"
         "float specula_erfc(float x) {\n"
         "  float t = 1.0 / (1.0 + 0.5 * x);\n"
         "  float p = -0.82215223 + t * 0.17087277;\n"
         "  p = 0.27886807 + t * (-1.13520398 + t * (1.48851587 + t * p));\n"
         "  p = 0.37409196 + t * (0.09678418 + t * (-0.18628806 + t * p));\n"
         "  return t * exp(-x * x - 1.26551223 + t * (1.00002368 + t * p));\n}";
}

/// What the shader files may name as ${name}: constants and series from C++, as literals of the
/// target's precision.
Placeholders computed_values(const Target& target) {
  namespace cheb = normalize::log_coef_chebyshev;
  const auto lit = [&](double value) { return target.literal(value); };
  return {{"pi", lit(kPi)},
          {"1/pi", lit(1 / kPi)},
          {"2 ln2", lit(2 * kLn2)},
          {"1/(2 ln2)", lit(1 / (2 * kLn2))},
          {"1/(2 pi ln2)", lit(1 / (2 * kPi * kLn2))},
          {"log_coef_j_series", chebyshev_function(target, "specula_log_coef_j", cheb::kJ, cheb::kJHigh)},
          {"log_coef_k_series", chebyshev_function(target, "specula_log_coef_k", cheb::kK, cheb::kKHigh)},
          {"erfc_function", erfc_function(target)}};
}

/// The name of the function `float NAME(float n)` that a coefficient file defines last.
std::string coefficient_function(std::string_view path) {
  const std::string_view text = shader_file(path);
  constexpr std::string_view kStart = "float ", kEnd = "(float n) {";
  std::string name;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line = text.substr(at, end - at);
    if (line.starts_with(kStart) && line.ends_with(kEnd))
      name = line.substr(kStart.size(), line.size() - kStart.size() - kEnd.size());
    at = end + 1;
  }
  if (name.empty()) throw std::logic_error(fmt::format("{} defines no float NAME(float n)", path));
  return name;
}

/// A form's cosine c(N, L, V): its file and function.
struct FormShader {
  std::string_view file;
  std::string_view function;
};

FormShader form_shader(Form form) {
  switch (form) {
    case Form::rv: return {"forms/rv.glsl", "specula_cos_rv"};
    case Form::nh: return {"forms/nh.glsl", "specula_cos_nh"};
  }
  throw std::logic_error("a form without its shader");
}

/// A built-in model's definition (families/<family>.h); nullptr for a user's model.
const families::ModelDefinition* builtin_definition(const Model& model) {
  return families::family_of(model.info()) ? families::find_builtin(model.id()).model : nullptr;
}

/// Adds a built-in lobe model's own k(n) and returns its function's name; "" when the model has
/// no coefficient file (k = 1).
std::string add_coef(ShaderSource& src, const Model& model) {
  const std::string_view path = builtin_definition(model)->glsl_file;
  if (path.empty()) return "";
  src.add_file(path);
  return coefficient_function(path);
}

/// The parameter list "float n, float s" of a model's entry function.
std::string parameter_list(const ModelInfo& info) {
  std::string list;
  for (const auto& p : info.params) list += fmt::format(", float {}", param_name(info, p));
  return list;
}

std::string parameter_names(const ModelInfo& info) {
  std::string names;
  for (const auto& p : info.params) names += (names.empty() ? "" : ", ") + param_name(info, p);
  return names;
}

/// A user lobe: `float specula_<id>_lobe(float c, its parameters)` from its formula (in c, or in
/// u = -log c); returns the call of it at `cosine`.
std::string add_formula_lobe(ShaderSource& src, const Target& target, const Model& model, std::string_view cosine) {
  const auto& definition = std::get<lobes::Formula>(model.lobe()).definition();
  const expr::Program& program = definition.in_cos ? *definition.in_cos : *definition.in_log_cos;
  const std::string name = entry_name(model) + "_lobe";
  src.add(name, fmt::format("// {}: the lobe F of a user-defined model ({}). Source: {}.\n"
                            "float {}(float c{}) {{\n  if (c <= 0.0) return 0.0;\n  c = min(c, 1.0);\n{}{}}}",
                            expr::comment_text(model.info().name), expr::comment_text(to_string(model.info().origin)),
                            expr::comment_text(model.info().source), name,
                            parameter_list(model.info()), program.reads(1) ? "  float u = -log(c);\n" : "",
                            program_lines(program, target.printer())));
  const std::string names = parameter_names(model.info());
  return fmt::format("{}({}(N, L, V){}{})", name, cosine, names.empty() ? "" : ", ", names);
}

/// The inputs of a user BRDF after N.L and N.V (FormulaBrdf::kInputs), those its formula reads.
std::string brdf_inputs(const expr::Program& program) {
  const bool nh = program.reads(2), vh = program.reads(3), lv = program.reads(4);
  std::string lines = nh || vh ? "  vec3 H = normalize(L + V);\n" : "";
  if (nh) lines += "  float nh = dot(N, H);\n";
  if (vh) lines += "  float vh = dot(V, H);\n";
  if (lv) lines += "  float lv = dot(L, V);\n";
  return lines;
}

/// A user BRDF's entry function, from its formula.
void add_formula_brdf(ShaderSource& src, const Target& target, const Model& model) {
  const expr::Program& program = *std::get<FormulaBrdf>(model.brdf()).program;
  src.add(entry_name(model),
          fmt::format("// {}: a user-defined BRDF ({}), f = {}. Source: {}.\n"
                      "float {}(vec3 N, vec3 L, vec3 V{}) {{\n  float nl = dot(N, L), nv = dot(N, V);\n"
                      "  if (nl <= 0.0 || nv <= 0.0) return 0.0;\n{}{}}}",
                      expr::comment_text(model.info().name), expr::comment_text(to_string(model.info().origin)),
                      expr::comment_text(model.info().summary), expr::comment_text(model.info().source),
                      entry_name(model), parameter_list(model.info()), brdf_inputs(program),
                      program_lines(program, target.printer())));
}

/// k as the model defines it, or the literal of an override (Model::with_coef).
std::string coefficient_expression(ShaderSource& src, const Target& target, const Model& model) {
  if (model.coef_overridden()) return target.literal(model.coef());
  if (std::holds_alternative<lobes::Formula>(model.lobe())) {
    if (model.info().coef_program) return coefficient_formula(*model.info().coef_program, target.printer());
    return model.info().normalization == Normalization::none ? "" : target.literal(model.coef());  // quadrature: baked
  }
  const std::string function = add_coef(src, model);
  if (function.empty() && model.info().normalization != Normalization::none)
    throw std::logic_error(fmt::format("no GLSL coefficient for model '{}'", model.id()));
  return function.empty() ? "" : function + "(n)";
}

/// f = k F(c): the form's cosine, the lobe (its family's file, or a user's formula) and k. In C++,
/// 0 below the horizon (N.L <= 0 or N.V <= 0), as Model is.
void add_lobe_entry(ShaderSource& src, const Target& target, const Model& model) {
  const FormShader form = form_shader(model.form());
  const families::Family* family = families::family_of(model.info());
  src.add_file(form.file);
  if (family) src.add_file(family->glsl.file);
  const std::string k = coefficient_expression(src, target, model);
  const std::string lobe_value =
      family ? fmt::format("{}({}(N, L, V), n{})", family->glsl.function, form.function, family->glsl.extra_args)
             : add_formula_lobe(src, target, model, form.function);
  src.add(entry_name(model),
          fmt::format("// {}: f = k F(c), {}, {} form. Source: {}; {}.\n"
                      "float {}(vec3 N, vec3 L, vec3 V{}) {{\n{}  return {};\n}}",
                      expr::comment_text(model.info().name), expr::comment_text(model.info().summary),
                      to_string(model.form()), expr::comment_text(model.info().source),
                      expr::comment_text(model.info().is_builtin() ? fmt::format("docs/math.md 2 `{}`", model.id())
                                                                   : to_string(model.info().origin)),
                      entry_name(model), parameter_list(model.info()),
                      target.in_double() ? "  if (dot(N, L) <= 0.0 || dot(N, V) <= 0.0) return 0.0;\n" : "",
                      k.empty() ? lobe_value : k + " * " + lobe_value));
}

void add_entry(ShaderSource& src, const Target& target, const Model& model);

/// M's Fresnel at the cosine `c` (a variable's name) as an expression, for turquin-f's scale
/// (the functions of brdfs/fresnel.glsl, which the caller adds).
std::string fresnel_expression(const Target& target, const fresnel::Channel& f, const std::string& c) {
  const auto lit = [&](double value) { return target.literal(value); };
  switch (f.kind) {
    case fresnel::Kind::one: return lit(1);
    case fresnel::Kind::schlick:
      return fmt::format("specula_fresnel_schlick_full({}, {}, {}, {})", c, lit(f.f0), lit(f.f90), lit(f.exponent));
    case fresnel::Kind::f82_tint: return fmt::format("specula_fresnel_f82({}, {}, {})", c, lit(f.f0), lit(f.tint));
    case fresnel::Kind::dielectric: return fmt::format("specula_fresnel_dielectric_eta({}, {})", c, lit(f.eta));
    case fresnel::Kind::conductor:
      return fmt::format("specula_fresnel_conductor({}, {}, {})", c, lit(f.eta), lit(f.kappa));
  }
  unreachable();
}

/// The compensated model's energy table as a function `<entry>_energy(mu)`: a chain of linear pieces
/// (no arrays: the same text in every shading language).
void add_energy_table(ShaderSource& src, const Target& target, const Model& model, const Compensated& compensated,
                      bool white) {
  const Model& base = *compensated.base;
  const EnergyTable& table = *compensated.table;
  const auto lit = [&](double value) { return target.literal(value); };
  const std::string name = entry_name(model), n = std::to_string(EnergyTable::kNodes);
  const auto& e = table.e;
  std::string pieces;
  for (std::size_t j = 0; j + 2 < e.size(); ++j)
    pieces += fmt::format("  if (t < {}.0) return {} + ({}) * (t - {}.0);\n", j + 1, lit(e[j]), lit(e[j + 1] - e[j]), j);
  pieces += fmt::format("  return {} + ({}) * (t - {}.0);\n", lit(e[e.size() - 2]), lit(e.back() - e[e.size() - 2]),
                        e.size() - 2);
  const std::string what = table.from_walk ? "1 - E_ms(mu), E_ms the random walk's multiply scattered albedo,"
                                           : "E(mu)";
  src.add(name + "_energy",
          fmt::format("// {} of {}{} at its parameters here, on {} nodes in s = mu^(1/3) (s = 1/{} ... 1), linear in s;\n"
                      "// max interpolation error {:.2g} ({}). Kulla & Conty 2017.\n"
                      "float {}_energy(float mu) {{\n  float t = pow(clamp(mu, 0.0, 1.0), 1.0 / 3.0) * {}.0 - 1.0;\n{}}}",
                      what, expr::comment_text(base.id()), white ? " with F0 = 1" : "", n, n, table.interpolation_error,
                      table.from_walk ? "against the walk, Heitz et al. 2016" : "specula lut", name, n, pieces));
}

/// M+ms, M+kulla-conty: M's entry, its energy table and the entry f_M + F_ms f_ms (models/compensated.h).
void add_added_entry(ShaderSource& src, const Target& target, const Model& model, const Compensated& compensated) {
  const Model& base = *compensated.base;
  const EnergyTable& table = *compensated.table;
  const bool coloured = compensated.fresnel_scale != 1;  // M's Fresnel below 1: E is M's at F0 = 1
  add_energy_table(src, target, model, compensated, coloured);
  const std::string name = entry_name(model);
  const double ms_factor = table.e_avg < 1 ? compensated.fresnel_scale / (kPi * (1 - table.e_avg)) : 0.0;
  const std::string names = parameter_names(base.info());
  const std::string fresnel =
      coloured ? fmt::format(", F_ms = F_avg^2 E_avg / (1 - F_avg (1 - E_avg)) = {:.9g}", compensated.fresnel_scale) : "";
  src.add(name, fmt::format("// {}: f = f_{} + {}(1 - E(N.L))(1 - E(N.V)) / (pi (1 - E_avg)), E_avg = {:.9g}{}; the table holds E\n"
                            "// at the parameter values it was made for only. Source: Kulla & Conty 2017.\n"
                            "float {}(vec3 N, vec3 L, vec3 V{}) {{\n  float nl = dot(N, L), nv = dot(N, V);\n"
                            "  if (nl <= 0.0 || nv <= 0.0) return 0.0;\n"
                            "  float ms = max(0.0, 1.0 - {}_energy(nl)) * max(0.0, 1.0 - {}_energy(nv)) * {};\n"
                            "  return {}(N, L, V{}{}) + ms;\n}}",
                            expr::comment_text(model.info().name), expr::comment_text(base.id()), coloured ? "F_ms " : "",
                            table.e_avg, fresnel, name,
                            parameter_list(model.info()), name, name,
                            target.literal(ms_factor), entry_name(base), names.empty() ? "" : ", ", names));
}

/// M+turquin-f0, -f, -favg, M+cycles: M's entry, its energy table with F = 1 and the entry
/// f_M (1 + F_s (1 − E(N·V)) / E(N·V)) (models/compensated.h).
void add_scaled_entry(ShaderSource& src, const Target& target, const Model& model, const Compensated& compensated) {
  const Model& base = *compensated.base;
  add_energy_table(src, target, model, compensated, compensated.fresnel.has_value() || compensated.fresnel_scale != 1);
  const std::string name = entry_name(model), names = parameter_names(base.info());
  const std::string f_s = compensated.fresnel ? fresnel_expression(target, *compensated.fresnel, "nv")
                                              : target.literal(compensated.fresnel_scale);
  if (compensated.fresnel) src.add_file("brdfs/fresnel.glsl");
  src.add(name, fmt::format("// {}: f = f_{} (1 + F_s (1 - E(N.V)) / E(N.V)), F_s = {}; not reciprocal. The table holds E\n"
                            "// at the parameter values it was made for only. Source: Turquin 2019.\n"
                            "float {}(vec3 N, vec3 L, vec3 V{}) {{\n  float nl = dot(N, L), nv = dot(N, V);\n"
                            "  if (nl <= 0.0 || nv <= 0.0) return 0.0;\n"
                            "  float e = {}_energy(nv);\n"
                            "  float scale = e > 0.0 ? 1.0 + {} * max(0.0, 1.0 - e) / e : 1.0;\n"
                            "  return {}(N, L, V{}{}) * scale;\n}}",
                            expr::comment_text(model.info().name), expr::comment_text(base.id()), expr::comment_text(f_s),
                            name, parameter_list(model.info()), name, f_s, entry_name(base), names.empty() ? "" : ", ",
                            names));
}

void add_compensated_entry(ShaderSource& src, const Target& target, const Model& model, const Compensated& compensated) {
  add_entry(src, target, *compensated.base);
  if (scales(compensated.scheme))
    add_scaled_entry(src, target, model, compensated);
  else
    add_added_entry(src, target, model, compensated);
}

/// The model's entry function `specula_<id>(N, L, V, parameters…)` and what it calls.
void add_entry(ShaderSource& src, const Target& target, const Model& model) {
  if (model.is_lobe())
    add_lobe_entry(src, target, model);
  else if (const Compensated* compensated = model.compensated())
    add_compensated_entry(src, target, model, *compensated);
  else if (const families::ModelDefinition* builtin = builtin_definition(model))
    src.add_file(builtin->glsl_file);
  else
    add_formula_brdf(src, target, model);
}

/// The entry's arguments from specula_brdf's vec4: the first four parameters; any beyond are
/// the model's values, baked in.
std::string entry_arguments(const Target& target, const Model& model) {
  constexpr const char* components[] = {"x", "y", "z", "w"};
  std::string args;
  for (std::size_t i = 0; i < model.params().size(); ++i)
    args += i < 4 ? fmt::format(", params.{}", components[i]) : ", " + target.literal(model.params()[i]);
  return args;
}

}  // namespace

namespace {

// The dialects' names, the one list parse_dialect and to_string read ("" outside the enum).
constexpr const char* name_of(Dialect dialect) noexcept {
  switch (dialect) {
    case Dialect::glsl330: return "glsl330";
    case Dialect::gles300: return "gles300";
    case Dialect::webgl2: return "webgl2";
  }
  return "";
}
static_assert(names_complete<Dialect, kDialectCount>(name_of));

}  // namespace

Dialect parse_dialect(std::string_view text) {
  if (const auto dialect = enum_named<Dialect, kDialectCount>(text, name_of)) return *dialect;
  throw InvalidArgument(fmt::format("unknown GLSL dialect '{}' (expected {})", text,
                                    names_listed<Dialect, kDialectCount>(name_of)));
}

const char* to_string(Dialect dialect) noexcept { return name_of(dialect); }

std::string version_header(Dialect dialect) {
  switch (dialect) {
    case Dialect::glsl330: return "#version 330 core\n";
    case Dialect::gles300:
    case Dialect::webgl2: return "#version 300 es\nprecision highp float;\nprecision highp int;\n";
  }
  unreachable();
}

namespace {

/// Names longer than this (an inline model's formula as its id) keep a prefix and a hash of the id:
/// glslang refuses identifiers over 1024 characters, and a name should stay readable.
constexpr std::size_t kMaxEntryName = 64;

std::string shortened(std::string name, std::string_view id) {
  if (name.size() <= kMaxEntryName) return name;
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits
  for (const char ch : id) hash = (hash ^ static_cast<unsigned char>(ch)) * 1099511628211ull;
  name.resize(kMaxEntryName - 17);
  if (name.back() == '_') name.pop_back();
  return fmt::format("{}_{:016x}", name, hash);
}

}  // namespace

std::string entry_name(const Model& model) {
  // GLSL identifiers: letters, digits and single underscores ("__" is reserved).
  std::string name = "specula_";
  for (const char ch : std::string_view(model.id())) {
    if (std::isalnum(static_cast<unsigned char>(ch))) name += ch;
    else if (name.back() != '_') name += '_';
  }
  if (name.back() == '_') name.pop_back();
  return shortened(name, model.id());
}

std::string float_literal(double value) {
  const auto single = static_cast<float>(value);
  if (!std::isfinite(single))
    throw InvalidArgument(fmt::format("no GLSL literal for {}: a float holds at most {:.8g}", value, FLT_MAX));
  std::string text = fmt::format("{:.9g}", single);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string double_literal(double value) {
  if (!std::isfinite(value)) throw InvalidArgument(fmt::format("no C++ literal for {}", value));
  std::string text = fmt::format("{}", value);
  if (text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

std::string param_name(const ModelInfo& info, const ParamInfo& p) {
  return info.is_builtin() ? p.name : glsl_param_name(p.name);
}

bool coef_is_baked(const Model& model) {
  if (!model.is_lobe()) return false;
  if (model.coef_overridden()) return true;
  const bool quadrature_k = std::holds_alternative<lobes::Formula>(model.lobe()) && !model.info().coef_program &&
                            model.info().normalization != Normalization::none;
  return quadrature_k;
}

std::string model_glsl(const Model& model) { return model_source(model, Language::glsl); }

std::string model_source(const Model& model, Language language) {
  const Target target{language};
  ShaderSource src(computed_values(target));
  add_entry(src, target, model);
  if (language != Language::cpp)
    src.add("specula_brdf",
            fmt::format("// The entry point renderers call: {} with params = ({}).\n"
                        "float specula_brdf(vec3 N, vec3 L, vec3 V, vec4 params) {{\n  return {}(N, L, V{});\n}}",
                        expr::comment_text(model.id()), parameter_names(model.info()), entry_name(model),
                        entry_arguments(target, model)));
  const std::string text = translate(src.take(), language);
  return language == Language::cpp ? std::string(cpp_support()) + text : text;
}

std::array<float, 4> model_params(const Model& model) {
  std::array<float, 4> packed{};
  for (std::size_t i = 0; i < model.params().size() && i < packed.size(); ++i)
    packed[i] = static_cast<float>(model.params()[i]);
  return packed;
}

}  // namespace specula::glsl
