// The shader exports: HLSL accepted by glslang's HLSL front end, Metal by g++ against a shim of the
// Metal types and functions they use, and BRDF Explorer files read as BRDF Explorer reads them and
// compiled inside a reproduction of its shader templates — for every model, with negative controls.
#include <gtest/gtest.h>

#include <regex>

#include "export_compilers.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exports/exports.h"
#include "specula/glsl/glsl.h"

namespace specula::exports {
namespace {

using testing::export_cases, testing::case_name, testing::validate_hlsl, testing::compile_metal, testing::read_brdf,
    testing::BrdfFile, testing::sphere_fragment, testing::angle_plot_vertex;

// ---- HLSL ---------------------------------------------------------------------------------------

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
