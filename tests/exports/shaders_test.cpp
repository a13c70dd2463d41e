// The shader exports: HLSL accepted by glslang's HLSL front end, Metal by g++ against a shim of the
// Metal types and functions they use, and BRDF Explorer files read as BRDF Explorer reads them and
// compiled inside a reproduction of its shader templates — for every model, with negative controls.
#include <gtest/gtest.h>

#include <regex>
#include <sstream>

#include "export_cases.h"
#include "glsl_support.h"
#include "specula/exports/exports.h"
#include "specula/glsl/glsl.h"
#include "text_support.h"

namespace specula::exports {
namespace {

using testing::export_cases, testing::case_name;

// ---- HLSL ---------------------------------------------------------------------------------------

/// A pixel shader that calls the export's specula_brdf with its parameters from a constant buffer.
std::string hlsl_shader(const std::string& exported) {
  return exported +
         "float4 u_params;\n"
         "float4 main(float4 position : SV_Position) : SV_Target {\n"
         "  float3 N = float3(0.0, 0.0, 1.0), L = normalize(float3(1.0, 0.0, 1.0));\n"
         "  return float4(specula_brdf(N, L, normalize(float3(-1.0, 0.2, 1.0)), u_params), 0.0, 0.0, 1.0);\n}\n";
}

testing::GlslCheck validate_hlsl(const std::string& exported) {
  return testing::validate_glsl(hlsl_shader(exported), "frag", "-D -V -S frag -e main -o /dev/null");
}

TEST(HlslExport, EveryModelCompilesInGlslangsHlslFrontEnd) {
  for (const Model& model : export_cases()) {
    const auto check = validate_hlsl(export_model(model, Format::hlsl));
    EXPECT_TRUE(check.ok) << case_name(model) << "\n" << check.log;
  }
}

// Negative controls: GLSL is no HLSL, and an export without one of its functions fails.
TEST(HlslExport, TheFrontEndRejectsGlslAndAnExportMissingAFunction) {
  const Model model = make_model("log-normalized");
  EXPECT_FALSE(validate_hlsl(glsl::model_glsl(model)).ok);
  const std::string without_series =
      std::regex_replace(export_model(model, Format::hlsl), std::regex("float specula_log_coef_j[^}]*\\}"), "");
  EXPECT_FALSE(validate_hlsl(without_series).ok);
  EXPECT_TRUE(validate_hlsl(export_model(model, Format::hlsl)).ok);
}

TEST(HlslExport, SpellsHlslsTypesConstantsAndFunctions) {
  const std::string log = export_model(make_model("log-normalized", {{"n", 50}}), Format::hlsl);
  EXPECT_NE(log.find("float specula_brdf(float3 N, float3 L, float3 V, float4 params)"), std::string::npos);
  EXPECT_NE(log.find("//   float f = specula_brdf(N, L, V, float4(50.0, 0.0, 0.0, 0.0));"), std::string::npos);
  const std::string phong = export_model(make_model("phong-normalized"), Format::hlsl);
  EXPECT_NE(phong.find("static const float SPECULA_PI = 3.14159274;"), std::string::npos);
  EXPECT_NE(export_model(make_model("blinn-phong"), Format::hlsl).find("rsqrt(len2)"), std::string::npos);
  EXPECT_EQ(log.find("vec3"), std::string::npos);
}

// ---- Metal --------------------------------------------------------------------------------------

// The Metal Shading Language is C++14 with its own types and library. This shim gives g++ what the
// exports use — float2/3/4 at global scope, the metal:: functions over float, program-scope
// `constant` — so that g++ checks their syntax, names, overloads and types. It cannot check
// Metal's own rules (address spaces beyond `constant`, no recursion, fast-math precision).
constexpr const char* kMetalShim = R"(#include <cmath>
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
std::string metal_unit(const std::vector<std::string>& exports) {
  std::string unit = kMetalShim;
  for (std::size_t i = 0; i < exports.size(); ++i)
    unit += fmt::format("namespace case{} {{\n{}\nfloat call() {{\n  float3 N(0, 0, 1), L(0.6f, 0, 0.8f), V(-0.6f, 0, 0.8f);\n"
                        "  return specula_brdf(N, L, V, float4(20, 1, 1, 1));\n}}\n}}\n",
                        i, exports[i]);
  return unit;
}

testing::GlslCheck compile_metal(const std::vector<std::string>& exports) {
  const testing::ScratchDir dir("msl");
  const auto file = dir.write("exports.cpp", metal_unit(exports));
  return testing::run_command(fmt::format("'{}' -std=c++14 -fsyntax-only -Wall -Wextra -Werror '{}'", SPECULA_CXX, file.string()));
}

TEST(MetalExport, EveryModelCompilesAgainstTheMetalShim) {
  std::vector<std::string> exports;
  for (const Model& model : export_cases()) exports.push_back(export_model(model, Format::msl));
  const auto check = compile_metal(exports);
  EXPECT_TRUE(check.ok) << check.log;
}

// Negative controls: GLSL's spellings, an unqualified built-in, or a missing function fail.
TEST(MetalExport, TheShimRejectsGlslAnUnqualifiedBuiltinAndAMissingFunction) {
  const Model model = make_model("ggx");
  const std::string metal = export_model(model, Format::msl);
  EXPECT_TRUE(compile_metal({metal}).ok);
  EXPECT_FALSE(compile_metal({glsl::model_glsl(model)}).ok);
  EXPECT_FALSE(compile_metal({std::regex_replace(metal, std::regex("metal::dot"), "dot")}).ok);
  EXPECT_FALSE(compile_metal({std::regex_replace(metal, std::regex("float2 specula_inclination[^}]*\\}"), "")}).ok);
}

TEST(MetalExport, QualifiesBuiltinsAndDeclaresConstantsInTheConstantAddressSpace) {
  const std::string phong = export_model(make_model("phong-normalized"), Format::msl);
  EXPECT_NE(phong.find("constant float SPECULA_PI = 3.14159274;"), std::string::npos);
  EXPECT_NE(phong.find("metal::pow(metal::min(c, 1.0), n)"), std::string::npos);
  EXPECT_NE(export_model(make_model("blinn-phong"), Format::msl).find("metal::rsqrt(len2)"), std::string::npos);
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

BrdfFile read_brdf(const std::string& text) {
  BrdfFile file;
  const auto lines = testing::lines_of(text);
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
std::string uniforms_and_shader(const BrdfFile& file) {
  std::string text;
  for (const auto& s : file.sliders) text += "uniform float " + s.name + ";\n";
  return text + "\n" + file.shader;
}

/// BRDF Explorer's lit-sphere fragment template (src/shaderTemplates/brdftemplatesphere.frag), in
/// our words: GLSL 4.10, the template's uniforms and inputs, the file's uniforms and shader, and a
/// main that shades a directional light as the template's does.
std::string sphere_fragment(const BrdfFile& file) {
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
std::string angle_plot_vertex(const BrdfFile& file) {
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

TEST(BrdfExplorerExport, EveryModelLoadsAndCompilesInTheTemplates) {
  for (const Model& model : export_cases()) {
    const BrdfFile file = read_brdf(export_model(model, Format::brdf));
    EXPECT_TRUE(file.ok && file.type == "analytic") << case_name(model);
    ASSERT_EQ(file.sliders.size(), model.params().size()) << case_name(model);
    for (std::size_t i = 0; i < file.sliders.size(); ++i) {
      const auto& s = file.sliders[i];
      const ParamInfo& p = model.info().params[i];
      EXPECT_TRUE(p.accepts(s.min) && p.accepts(s.max) && s.min < s.max) << case_name(model) << " " << s.name;
      EXPECT_TRUE(s.min <= s.value && s.value <= s.max && s.value == model.params()[i]) << case_name(model);
    }
    for (const auto& [source, stage] : {std::pair{sphere_fragment(file), "frag"}, {angle_plot_vertex(file), "vert"}}) {
      const auto check = testing::validate_glsl(source, stage);
      EXPECT_TRUE(check.ok) << case_name(model) << " " << stage << "\n" << check.log;
    }
  }
}

// Negative controls: the shader without the template's uniforms for its sliders, or without its
// BRDF entry, fails; so does a file whose parameters section is not closed.
TEST(BrdfExplorerExport, TheTemplateRejectsAShaderWithoutItsUniformsOrEntry) {
  const std::string text = export_model(make_model("schlick-modified"), Format::brdf);
  BrdfFile file = read_brdf(text);
  ASSERT_TRUE(testing::validate_glsl(sphere_fragment(file), "frag").ok);
  BrdfFile without_sliders = file;
  without_sliders.sliders.clear();
  EXPECT_FALSE(testing::validate_glsl(sphere_fragment(without_sliders), "frag").ok);
  BrdfFile without_entry = file;
  without_entry.shader = std::regex_replace(file.shader, std::regex("vec3 BRDF\\("), "vec3 brdf(");
  EXPECT_FALSE(testing::validate_glsl(sphere_fragment(without_entry), "frag").ok);
  EXPECT_FALSE(read_brdf(std::regex_replace(text, std::regex("::end parameters"), "")).ok);
}

TEST(BrdfExplorerExport, SlidersSitInsideTheDocumentedRanges) {
  const auto sliders = read_brdf(export_model(make_model("ggx", {{"alpha", 0.2}}), Format::brdf)).sliders;
  ASSERT_EQ(sliders.size(), 2u);
  EXPECT_EQ(sliders[0].name, "alpha");
  EXPECT_EQ((std::array{sliders[0].min, sliders[0].max, sliders[0].value}), (std::array{0.001, 1.0, 0.2}));
  const ParamInfo n{"n", 20, 0, 1e9, true, ""};
  EXPECT_EQ(slider_range(n, 20).min, 1);
  EXPECT_EQ(slider_range(n, 20).max, 1000);
  EXPECT_EQ(slider_range(n, 5000).max, 5000);  // widened to hold the value
  EXPECT_EQ(slider_range(n, 0.25).min, 0.25);
  const ParamInfo inline_param{"a", 1, -1.7e308, 1.7e308, false, ""};
  EXPECT_EQ(slider_range(inline_param, 1).min, 0);
  EXPECT_EQ(slider_range(inline_param, 1).max, 50);
  const std::string user = export_model(make_model("lobe: c^n", {{"n", 8}}), Format::brdf);
  EXPECT_NE(user.find("float p_n 0 400 8\n"), std::string::npos) << user;
  EXPECT_NE(user.find("return vec3(specula_lobe_c_n(N, L, V, p_n));"), std::string::npos) << user;
}

}  // namespace
}  // namespace specula::exports
