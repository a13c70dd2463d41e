// The model's GLSL in HLSL, Metal and C++ (src/glsl/dialect.h): a rewrite word by word, outside
// comments, by the tables below.
#include "dialect.h"

#include <array>
#include <cctype>
#include <fmt/format.h>
#include <span>
#include <stdexcept>

namespace specula::glsl {
namespace {

/// A word of GLSL and its spelling in HLSL, Metal and C++.
struct Word {
  std::string_view glsl, hlsl, msl, cpp;

  std::string_view in(Language language) const noexcept {
    switch (language) {
      case Language::glsl: return glsl;
      case Language::hlsl: return hlsl;
      case Language::msl: return msl;
      case Language::cpp: return cpp;
    }
    unreachable();
  }
};

// The types. C++ has no Vec4: the vec4 entry specula_brdf is not emitted there.
constexpr std::array kTypes{
    Word{"float", "float", "float", "double"},
    Word{"vec2", "float2", "float2", "Vec2"},
    Word{"vec3", "float3", "float3", "Vec3"},
    Word{"vec4", "float4", "float4", "Vec4"},
};

// The built-in functions the shader files and expr::to_glsl call. Metal's are namespace members.
constexpr std::array kBuiltins{
    Word{"abs", "abs", "metal::abs", "abs"},
    Word{"acos", "acos", "metal::acos", "acos"},
    Word{"asin", "asin", "metal::asin", "asin"},
    Word{"clamp", "clamp", "metal::clamp", "clamp"},
    Word{"cos", "cos", "metal::cos", "cos"},
    Word{"cross", "cross", "metal::cross", "cross"},
    Word{"dot", "dot", "metal::dot", "dot"},
    Word{"erfc", "", "", "erfc"},  // the C++ target's specula_erfc only (glsl.cpp: erfc_function)
    Word{"exp", "exp", "metal::exp", "exp"},
    Word{"exp2", "exp2", "metal::exp2", "exp2"},
    Word{"inversesqrt", "rsqrt", "metal::rsqrt", "inversesqrt"},
    Word{"log", "log", "metal::log", "log"},
    Word{"log2", "log2", "metal::log2", "log2"},
    Word{"max", "max", "metal::max", "max"},
    Word{"min", "min", "metal::min", "min"},
    Word{"normalize", "normalize", "metal::normalize", "normalize"},
    Word{"pow", "pow", "metal::pow", "pow"},
    Word{"sin", "sin", "metal::sin", "sin"},
    Word{"sqrt", "sqrt", "metal::sqrt", "sqrt"},
};

// Words that may stand before "(" without being a call.
constexpr std::array<std::string_view, 4> kKeywords{"if", "for", "while", "return"};

/// A global constant's qualifier in each language.
constexpr Word kGlobalConst{"const", "static const", "constant", "inline constexpr"};

const Word* find_word(std::span<const Word> words, std::string_view glsl) {
  for (const Word& word : words)
    if (word.glsl == glsl) return &word;
  return nullptr;
}

bool is_word_char(char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; }

/// One identifier of code in `language`; `called` when "(" follows it.
std::string respelled(std::string_view word, bool called, Language language) {
  if (const Word* type = find_word(kTypes, word)) return std::string(type->in(language));
  if (!called || word.starts_with("specula_")) return std::string(word);
  if (const Word* builtin = find_word(kBuiltins, word)) return std::string(builtin->in(language));
  for (const std::string_view keyword : kKeywords)
    if (word == keyword) return std::string(word);
  throw std::logic_error(fmt::format("GLSL function '{}' has no translation (src/glsl/dialect.cpp)", word));
}

/// Code without comments: each identifier respelled; numbers (1e-3 included) kept.
std::string translate_code(std::string_view code, Language language) {
  std::string out;
  for (std::size_t at = 0; at < code.size();) {
    std::size_t end = at;
    while (end < code.size() && is_word_char(code[end])) ++end;
    if (end == at) {
      out += code[at++];
      continue;
    }
    const std::string_view word = code.substr(at, end - at);
    // Numbers (1e-3 too) and the members of a namespace (std::log1p, from expr::to_cpp) stay.
    const bool kept = std::isdigit(static_cast<unsigned char>(word[0])) || out.ends_with("::");
    out += kept ? std::string(word) : respelled(word, end < code.size() && code[end] == '(', language);
    at = end;
  }
  return out;
}

/// A line: its global `const` qualified, C++ functions made inline, its code translated.
std::string translate_line(std::string_view line, Language language) {
  const std::size_t comment = line.find("//");
  std::string_view code = line.substr(0, comment);
  std::string out;
  if (code.starts_with("const ")) {
    out = std::string(kGlobalConst.in(language));
    code.remove_prefix(kGlobalConst.glsl.size());
  } else if (language == Language::cpp && !code.empty() && code.ends_with('{') && find_word(kTypes, code.substr(0, code.find(' ')))) {
    out = "inline ";
  }
  out += translate_code(code, language);
  if (comment != std::string_view::npos) out += line.substr(comment);
  return out;
}

}  // namespace

std::string translate(std::string_view glsl, Language language) {
  if (language == Language::glsl) return std::string(glsl);
  std::string out;
  for (std::size_t at = 0; at < glsl.size();) {
    const std::size_t end = std::min(glsl.find('\n', at), glsl.size());
    out += translate_line(glsl.substr(at, end - at), language);
    if (end < glsl.size()) out += '\n';
    at = end + 1;
  }
  return out;
}

std::string_view cpp_support() {
  return R"(// GLSL's vectors and built-in functions in double, for the functions below (specula export --format cpp).
struct Vec2 {
  double x = 0, y = 0;
  constexpr Vec2() = default;
  constexpr Vec2(double x_, double y_) : x(x_), y(y_) {}
};
struct Vec3 {
  double x = 0, y = 0, z = 0;
  constexpr Vec3() = default;
  constexpr Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
};
inline Vec2 operator/(const Vec2& a, double s) { return {a.x / s, a.y / s}; }
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(const Vec3& a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline Vec3 operator*(const Vec3& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator/(const Vec3& a, double s) { return {a.x / s, a.y / s, a.z / s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double inversesqrt(double x) { return 1.0 / std::sqrt(x); }
inline Vec3 normalize(const Vec3& a) { return a * inversesqrt(dot(a, a)); }
inline double min(double a, double b) { return b < a ? b : a; }
inline double max(double a, double b) { return a < b ? b : a; }
inline double clamp(double x, double lo, double hi) { return min(max(x, lo), hi); }
inline double abs(double x) { return std::fabs(x); }
inline double pow(double x, double y) { return std::pow(x, y); }
inline double exp(double x) { return std::exp(x); }
inline double erfc(double x) { return std::erfc(x); }
inline double exp2(double x) { return std::exp2(x); }
inline double log(double x) { return std::log(x); }
inline double log2(double x) { return std::log2(x); }
inline double sqrt(double x) { return std::sqrt(x); }
inline double sin(double x) { return std::sin(x); }
inline double cos(double x) { return std::cos(x); }
inline double acos(double x) { return std::acos(x); }
inline double asin(double x) { return std::asin(x); }
)";
}

}  // namespace specula::glsl
