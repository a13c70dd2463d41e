#include "specula/fit/emit.h"

#include <cctype>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <set>

#include "specula/exceptions.h"
#include "specula/expr/comment.h"

namespace specula::fit {
namespace {

// Names a variable cannot have in the emitted language (the common reserved words).
const std::set<std::string_view>& reserved_words(std::string_view language) {
  static const std::set<std::string_view> cpp{
      "auto", "bool", "break", "case", "char", "class", "const", "constexpr", "continue",
      "default", "delete", "do", "double", "else", "enum", "explicit", "extern", "false",
      "float", "for", "friend", "goto", "if", "inline", "int", "long", "namespace", "new",
      "operator", "private", "protected", "public", "register", "return", "short", "signed",
      "sizeof", "static", "struct", "switch", "template", "this", "throw", "true", "try",
      "typedef", "typename", "union", "unsigned", "using", "virtual", "void", "volatile",
      "while", "and", "or", "not", "xor", "std"};
  static const std::set<std::string_view> glsl{
      "attribute", "const", "uniform", "varying", "buffer", "shared", "layout", "centroid",
      "flat", "smooth", "break", "continue", "do", "for", "while", "switch", "case", "default",
      "if", "else", "in", "out", "inout", "float", "double", "int", "void", "bool", "true",
      "false", "invariant", "precise", "discard", "return", "mat2", "mat3", "mat4", "vec2",
      "vec3", "vec4", "ivec2", "ivec3", "ivec4", "bvec2", "bvec3", "bvec4", "uint", "uvec2",
      "uvec3", "uvec4", "lowp", "mediump", "highp", "precision", "sampler2D", "struct",
      "input", "output", "filter", "sizeof", "cast", "namespace", "using", "common", "partition",
      "active", "long", "short", "half", "fixed", "unsigned", "superp", "public", "static",
      "extern", "external", "interface", "asm", "class", "union", "enum", "typedef", "template",
      "this", "goto", "inline", "noinline", "volatile", "packed", "radians", "degrees", "tan",
      "asin", "atan", "pow", "exp", "log", "exp2", "log2", "sqrt", "inversesqrt", "sign",
      "floor", "ceil", "fract", "mod", "min", "max", "clamp", "mix", "step", "smoothstep",
      "length", "distance", "dot", "cross", "normalize", "reflect", "refract"};
  static const std::set<std::string_view> python{
      "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class",
      "continue", "def", "del", "elif", "else", "except", "finally", "for", "from", "global",
      "if", "import", "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return",
      "try", "while", "with", "yield", "math"};
  static const std::set<std::string_view> none;
  return language == "cpp" ? cpp : language == "glsl" ? glsl : language == "python" ? python : none;
}

/// One line of text (expr::comment_text's) as the body of a Python string literal.
std::string python_string_body(std::string_view line) {
  std::string out;
  for (const char ch : line) {
    if (ch == '\\' || ch == '"') out += '\\';
    out += ch;
  }
  return out;
}

std::vector<std::string> typed(const std::vector<std::string>& variables, std::string_view type) {
  std::vector<std::string> params;
  for (const auto& v : variables) params.push_back(fmt::format("{} {}", type, v));
  return params;
}

}  // namespace

void check_language(std::string_view language) {
  if (language != "cpp" && language != "glsl" && language != "latex" && language != "python")
    throw InvalidArgument(fmt::format("the language must be cpp, glsl, latex or python, got '{}'", language));
}

std::string function_name(std::string_view target) {
  std::string name = "fitted_";
  for (char ch : target) name += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return name;
}

void check_emittable(const std::vector<std::string>& variables, std::string_view language) {
  for (const auto& v : variables) {
    const bool glsl_reserved = language == "glsl" && (v.starts_with("gl_") || v.find("__") != std::string::npos);
    if (reserved_words(language).contains(v) || glsl_reserved)
      throw InvalidArgument(fmt::format(
          "column '{}' is a reserved word in {}: rename it to emit the formula", v, language));
  }
}

std::string emit_function(const expr::Expression& formula, std::string_view language,
                          std::string_view target, std::string_view origin) {
  check_language(language);
  const auto& vars = formula.variables();
  const std::string name = function_name(target);
  const std::string comment = expr::comment_text(origin);
  if (language == "cpp")
    return fmt::format("// {}\ninline double {}({}) {{ return {}; }}\n", comment, name,
                       fmt::join(typed(vars, "double"), ", "), expr::to_cpp(formula));
  if (language == "glsl")
    return fmt::format("// {}\nfloat {}({}) {{ return {}; }}\n", comment, name,
                       fmt::join(typed(vars, "float"), ", "), expr::to_glsl(formula));
  if (language == "python")
    return fmt::format("import math\n\n\ndef {}({}):\n    \"\"\"{}\"\"\"\n    return {}\n", name,
                       fmt::join(vars, ", "), python_string_body(comment), expr::to_python(formula));
  return fmt::format("% {}\n{} = {}\n", comment, target, expr::to_latex(formula));
}

}  // namespace specula::fit
