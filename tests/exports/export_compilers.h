#pragma once
// The compilers the export tests run an export through, each with the text around it that its
// consumer adds: HLSL in a pixel shader for glslang's HLSL front end, Metal against a g++ shim, a
// .brdf file read as BRDF Explorer reads it and put in its shader templates, a C++ header in a
// translation unit of g++, and model_glsl's functions in a GLSL fragment shader. Several exports
// go to one g++ run where the language allows (namespaces), to keep the tests fast.
#include <fmt/format.h>
#include <sstream>
#include <string>
#include <vector>

#include "export_cases.h"
#include "glsl_support.h"
#include "text_support.h"

namespace specula::testing {

// ---- HLSL ---------------------------------------------------------------------------------------

/// A pixel shader that calls the export's specula_brdf with its parameters from a constant buffer.
inline std::string hlsl_shader(const std::string& exported) {
  return exported +
         "float4 u_params;\n"
         "float4 main(float4 position : SV_Position) : SV_Target {\n"
         "  float3 N = float3(0.0, 0.0, 1.0), L = normalize(float3(1.0, 0.0, 1.0));\n"
         "  return float4(specula_brdf(N, L, normalize(float3(-1.0, 0.2, 1.0)), u_params), 0.0, 0.0, 1.0);\n}\n";
}

inline GlslCheck validate_hlsl(const std::string& exported) {
  return validate_glsl(hlsl_shader(exported), "frag", "-D -V -S frag -e main -o /dev/null");
}

// ---- Metal --------------------------------------------------------------------------------------

// The Metal Shading Language is C++14 with its own types and library. This shim gives g++ what the
// exports use — float2/3/4 at global scope, the metal:: functions over float, program-scope
// `constant` — so that g++ checks their syntax, names, overloads and types. It cannot check
// Metal's own rules (address spaces beyond `constant`, no recursion, fast-math precision).
inline constexpr const char* kMetalShim = R"(#include <cmath>
#define constant const
struct float2 { float x, y; float2(float a, float b) : x(a), y(b) {} };
struct float3 { float x, y, z; float3(float a, float b, float c) : x(a), y(b), z(c) {} };
struct float4 { float x, y, z, w; float4(float a, float b, float c, float d) : x(a), y(b), z(c), w(d) {} };
inline float2 operator/(float2 a, float s) { return float2(a.x / s, a.y / s); }
inline float3 operator+(float3 a, float3 b) { return float3(a.x + b.x, a.y + b.y, a.z + b.z); }
inline float3 operator-(float3 a, float3 b) { return float3(a.x - b.x, a.y - b.y, a.z - b.z); }
inline float3 operator*(float s, float3 a) { return float3(s * a.x, s * a.y, s * a.z); }
inline float3 operator*(float3 a, float s) { return s * a; }
namespace metal {
inline float abs(float x) { return std::fabs(x); }
inline float acos(float x) { return std::acos(x); }
inline float asin(float x) { return std::asin(x); }
inline float cos(float x) { return std::cos(x); }
inline float sin(float x) { return std::sin(x); }
inline float exp(float x) { return std::exp(x); }
inline float exp2(float x) { return std::exp2(x); }
inline float log(float x) { return std::log(x); }
inline float log2(float x) { return std::log2(x); }
inline float sqrt(float x) { return std::sqrt(x); }
inline float rsqrt(float x) { return 1 / std::sqrt(x); }
inline float pow(float x, float y) { return std::pow(x, y); }
inline float min(float a, float b) { return b < a ? b : a; }
inline float max(float a, float b) { return a < b ? b : a; }
inline float clamp(float x, float lo, float hi) { return min(max(x, lo), hi); }
inline float dot(float3 a, float3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline float3 cross(float3 a, float3 b) { return float3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }
inline float3 normalize(float3 a) { return a * rsqrt(dot(a, a)); }
}  // namespace metal
)";

/// One translation unit: the shim, then each export in a namespace of its own with a function
/// that calls its specula_brdf.
inline std::string metal_unit(const std::vector<std::string>& exports) {
  std::string unit = kMetalShim;
  for (std::size_t i = 0; i < exports.size(); ++i)
    unit += fmt::format("namespace case{} {{\n{}\nfloat call() {{\n  float3 N(0, 0, 1), L(0.6f, 0, 0.8f), V(-0.6f, 0, 0.8f);\n"
                        "  return specula_brdf(N, L, V, float4(20, 1, 1, 1));\n}}\n}}\n",
                        i, exports[i]);
  return unit;
}

/// g++ in C++14 over metal_unit, every warning an error but an unused parameter: the specula_brdf
/// of a model without parameters ignores its `params`, as GLSL and HLSL let it.
inline GlslCheck compile_metal(const std::vector<std::string>& exports) {
  const ScratchDir dir("msl");
  const auto file = dir.write("exports.cpp", metal_unit(exports));
  return run_command(fmt::format("'{}' -std=c++14 -fsyntax-only -Wall -Wextra -Werror -Wno-unused-parameter '{}'",
                                 SPECULA_CXX, file.string()));
}

// ---- BRDF Explorer ------------------------------------------------------------------------------

/// A .brdf file as BRDF Explorer's loader (BRDFBase::loadBRDF) reads it: the first word of the first
/// line is the type; then, skipping blank lines and lines starting with '#', `::begin NAME` …
/// `::end NAME` sections; each parameter line `float NAME MIN MAX DEFAULT`, the shader's lines kept.
struct BrdfFile {
  std::string type;
  struct Slider {
    std::string name;
    double min, max, value;
  };
  std::vector<Slider> sliders;
  std::string shader;
  bool ok = true;
};

inline BrdfFile read_brdf(const std::string& text) {
  BrdfFile file;
  const auto lines = lines_of(text);
  file.type = lines.empty() ? "" : lines[0].substr(0, lines[0].find(' '));
  std::string section;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::istringstream words(lines[i]);
    std::string first;
    if (!(words >> first) || first[0] == '#') continue;
    std::string name;
    if (first == "::begin" || first == "::end") {
      words >> name;
      file.ok &= first == "::begin" ? section.empty() : name == section;
      section = first == "::begin" ? name : "";
    } else if (section == "parameters") {
      BrdfFile::Slider slider;
      file.ok &= first == "float" && static_cast<bool>(words >> slider.name >> slider.min >> slider.max >> slider.value);
      file.sliders.push_back(slider);
    } else if (section == "shader") {
      file.shader += lines[i] + "\n";
    }
  }
  file.ok &= section.empty();
  return file;
}

/// What BRDF Explorer puts in a template for ::INSERT_UNIFORMS_HERE:: (a uniform per slider) and
/// ::INSERT_BRDF_FUNCTION_HERE:: (the shader).
inline std::string uniforms_and_shader(const BrdfFile& file) {
  std::string text;
  for (const auto& s : file.sliders) text += "uniform float " + s.name + ";\n";
  return text + "\n" + file.shader;
}

/// BRDF Explorer's lit-sphere fragment template (src/shaderTemplates/brdftemplatesphere.frag), in
/// our words: GLSL 4.10, the template's uniforms and inputs, the file's uniforms and shader, and a
/// main that shades a directional light as the template's does.
inline std::string sphere_fragment(const BrdfFile& file) {
  return "#version 410\nuniform vec3 incidentVector;\nuniform float incidentTheta;\nuniform float incidentPhi;\n"
         "uniform float brightness;\nuniform float gamma;\nuniform float exposure;\nuniform float useNDotL;\n"
         "in vec4 worldSpaceVert;\nin vec4 eyeSpaceVert;\nout vec4 fragColor;\n" +
         uniforms_and_shader(file) +
         "\nvoid main(void) {\n  vec3 normal = normalize(worldSpaceVert.xyz);\n"
         "  vec3 tangent = normalize(cross(vec3(0, 1, 0), normal));\n  vec3 bitangent = normalize(cross(normal, tangent));\n"
         "  vec3 b = max(BRDF(incidentVector, vec3(0, 0, 1), normal, tangent, bitangent), vec3(0.0));\n"
         "  if (useNDotL != 0) b *= dot(normal, incidentVector);\n"
         "  b = pow(b * brightness * pow(2.0, exposure), vec3(1.0 / gamma));\n"
         "  fragColor = vec4(clamp(b, vec3(0.0), vec3(1.0)), 1.0);\n}\n";
}

/// Its angle-plot vertex template (brdftemplateAnglePlot.vert), which calls BRDF in a vertex shader.
inline std::string angle_plot_vertex(const BrdfFile& file) {
  return "#version 410\nuniform mat4 projectionMatrix;\nuniform mat4 modelViewMatrix;\nuniform vec3 incidentVector;\n"
         "uniform float incidentTheta;\nuniform float incidentPhi;\nuniform float useLogPlot;\nuniform float useNDotL;\n"
         "uniform float phiV;\nuniform vec3 colorMask;\nin vec3 vtx_position;\n" +
         uniforms_and_shader(file) +
         "\nvoid main(void) {\n  vec4 inPos = vec4(vtx_position.xy, 0, 1);\n"
         "  float yAngle = -vtx_position.z;\n"
         "  vec3 viewingVector = normalize(vec3(sin(yAngle) * cos(phiV), sin(yAngle) * sin(phiV), cos(yAngle)));\n"
         "  float b = dot(BRDF(normalize(incidentVector), viewingVector, vec3(0, 0, 1), vec3(1, 0, 0), vec3(0, 1, 0)), colorMask);\n"
         "  inPos.y = useLogPlot > 0.5 ? log(b + 1.0) * 0.434294482 : b;\n"
         "  gl_Position = projectionMatrix * (modelViewMatrix * inPos);\n}\n";
}

// ---- C++ and GLSL -------------------------------------------------------------------------------

/// C++ headers (export_model's cpp), each in a namespace of its own in one translation unit,
/// checked by g++ with every warning an error.
inline GlslCheck compile_cpp_headers(const std::vector<std::string>& headers) {
  const ScratchDir dir("cpp-syntax");
  std::string unit;
  for (std::size_t i = 0; i < headers.size(); ++i) {
    dir.write(fmt::format("case{}.h", i), headers[i]);
    unit += fmt::format("namespace case{} {{\n#include \"case{}.h\"\n}}\n", i, i);
  }
  const auto file = dir.write("unit.cpp", "#include <cmath>\n" + unit);
  return run_command(fmt::format("'{}' -std=c++20 -fsyntax-only -Wall -Wextra -Wpedantic -Werror '{}'", SPECULA_CXX, file.string()));
}

/// GLSL functions that define specula_brdf (model_glsl, queries::glsl_function) in a GLSL 3.30
/// fragment shader that calls it.
inline std::string glsl_function_shader(const std::string& functions) {
  return "#version 330 core\n" + functions +
         "uniform vec4 u_params;\nout vec4 color;\nvoid main() {\n"
         "  vec3 N = vec3(0.0, 0.0, 1.0), L = normalize(vec3(1.0, 0.0, 1.0));\n"
         "  color = vec4(specula_brdf(N, L, normalize(vec3(-1.0, 0.2, 1.0)), u_params));\n}\n";
}

/// glslangValidator over shaders of one stage in one run, each compiled on its own (no -l, no
/// linking): ok when every one passes; the log names a failing one by its file, case<i>.<stage>.
inline GlslCheck validate_each_glsl(const std::vector<std::string>& shaders, const std::string& stage) {
  const ScratchDir dir("glsl");
  std::string files;
  for (std::size_t i = 0; i < shaders.size(); ++i)
    files += fmt::format(" '{}'", dir.write(fmt::format("case{}.{}", i, stage), shaders[i]).string());
  return run_command(fmt::format("'{}'{}", SPECULA_GLSLANG, files));
}

}  // namespace specula::testing
