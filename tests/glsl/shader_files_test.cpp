// The GLSL files of src/glsl/shaders/ (src/glsl/shader_files.h, core's: the models) and of
// src/render/shaders/ (src/render/shader_files.h, render's: the scene shader): each cites its source
// on its first line and is ASCII; each is part of some emitted shader (no family's file lies
// unused); the scene shader's files are render's alone; each coefficient file belongs to a
// normalized lobe model; and how a shader is put together from them (includes once and first,
// placeholders filled), with the failures of each.
#include "src/glsl/shader_files.h"

#include <gtest/gtest.h>

#include <regex>
#include <stdexcept>
#include <vector>

#include "specula/catalogue/catalogue.h"
#include "specula/render/scene_shader.h"
#include "src/render/shader_files.h"

namespace specula::glsl {
namespace {

/// Every embedded GLSL file: core's, then render's.
std::vector<ShaderFile> all_files() {
  std::vector<ShaderFile> all(embedded_shaders().begin(), embedded_shaders().end());
  all.insert(all.end(), render::embedded_shaders().begin(), render::embedded_shaders().end());
  return all;
}

TEST(ShaderFiles, EachCitesItsSourceOnItsFirstLineAndIsAscii) {
  // A year (the paper's), or the specula source or docs/math.md section it implements.
  const std::regex citation(R"(^// .*(\b(1[6-9]|20)\d\d\b|docs/|render/|gl/).*)");
  ASSERT_GE(all_files().size(), 30u);
  for (const ShaderFile& file : all_files()) {
    EXPECT_TRUE(file.path.ends_with(".glsl")) << file.path;
    for (const char ch : file.text) ASSERT_LT(static_cast<unsigned char>(ch), 0x80) << file.path;
    const std::string first(file.text.substr(0, file.text.find('\n')));
    EXPECT_TRUE(std::regex_match(first, citation)) << file.path << ": " << first;
  }
}

/// Every shader specula emits: the vertex shader and each model's scene shader (which holds its
/// model_glsl), in every form, but for the models `left_out`.
std::string emitted_shaders(const std::vector<std::string>& left_out = {}) {
  std::string all = render::scene_vertex_shader(Dialect::glsl330);
  for (const auto& info : models()) {
    if (std::find(left_out.begin(), left_out.end(), info.id) != left_out.end()) continue;
    if (info.kind == ModelKind::brdf) {
      all += render::scene_fragment_shader(make_model(info.id), Dialect::glsl330);
      continue;
    }
    for (const Form form : {Form::rv, Form::nh})
      all += render::scene_fragment_shader(make_model(info.id, {}, form), Dialect::glsl330);
  }
  return all;
}

/// The files whose first line is in none of `shaders`.
std::vector<std::string> unused_files(const std::string& shaders) {
  std::vector<std::string> unused;
  for (const ShaderFile& file : all_files())
    if (shaders.find(file.text.substr(0, file.text.find('\n') + 1)) == std::string::npos)
      unused.emplace_back(file.path);
  return unused;
}

TEST(ShaderFiles, EachIsPartOfAnEmittedShader) {
  EXPECT_EQ(unused_files(emitted_shaders()), std::vector<std::string>{});
  // The negative control: without the Lambert and log-paper models, their files are unused.
  EXPECT_EQ(unused_files(emitted_shaders({"lambert", "log-paper"})),
            (std::vector<std::string>{"brdfs/lambert.glsl", "coefficients/log-paper.glsl"}));
}

// Core carries the models' GLSL and render the scene shader's: no scene file is core's.
TEST(ShaderFiles, TheSceneShaderFilesAreRendersAlone) {
  for (const ShaderFile& file : embedded_shaders()) EXPECT_FALSE(file.path.starts_with("scene/")) << file.path;
  std::vector<std::string> scene;
  for (const ShaderFile& file : render::embedded_shaders()) scene.emplace_back(file.path);
  EXPECT_EQ(scene, (std::vector<std::string>{"scene/display.glsl", "scene/geometry.glsl", "scene/main.glsl",
                                             "scene/shading.glsl", "scene/uniforms.glsl", "scene/vertex.glsl"}));
  // Each library's files are found among its own only.
  EXPECT_NE(find_shader_file(render::embedded_shaders(), "scene/main.glsl"), nullptr);
  EXPECT_EQ(find_shader_file("scene/main.glsl"), nullptr);
  EXPECT_EQ(find_shader_file(render::embedded_shaders(), "lobes/log.glsl"), nullptr);
  ShaderSource scene_source({}, render::embedded_shaders());
  EXPECT_THROW(scene_source.add_file("lobes/log.glsl"), std::logic_error);
}

TEST(ShaderFiles, EachCoefficientFileBelongsToANormalizedLobeModel) {
  int coefficients = 0;
  for (const ShaderFile& file : embedded_shaders()) {
    if (!file.path.starts_with("coefficients/")) continue;
    ++coefficients;
    const std::string_view id = file.path.substr(13, file.path.size() - 13 - 5);
    const ModelInfo* info = find_model(id);
    ASSERT_NE(info, nullptr) << file.path << " names no model";
    EXPECT_EQ(info->kind, ModelKind::lobe) << file.path;
    EXPECT_NE(info->normalization, Normalization::none) << file.path;
  }
  EXPECT_EQ(coefficients, 7);
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(ShaderSource, IncludesComeFirstAndOnce) {
  ShaderSource src(Placeholders{{"pi", "3.0"}});
  src.add_file("brdfs/ward-duer.glsl");
  src.add_file("brdfs/ward-gmd.glsl");
  src.add_file("brdfs/ward-duer.glsl");
  const std::string text = src.take();
  EXPECT_EQ(text.find("#include"), std::string::npos);
  EXPECT_EQ(count(text, "const float SPECULA_PI = 3.0;"), 1u);
  EXPECT_EQ(count(text, "vec2 specula_inclination("), 1u);
  EXPECT_EQ(count(text, "float specula_ward_duer("), 1u);
  std::size_t previous = 0;
  for (const char* name : {"SPECULA_PI =", "vec2 specula_inclination(", "float specula_ward_gaussian(",
                           "float specula_ward_duer(", "float specula_ward_gmd("}) {
    const std::size_t at = text.find(name);
    ASSERT_NE(at, std::string::npos) << name;
    EXPECT_GT(at, previous) << name;
    previous = at;
  }
}

TEST(ShaderSource, PlaceholdersAndMissingFilesFailLoudly) {
  EXPECT_EQ(fill("a ${x} b ${1/(2 ln2)}.", {{"x", "1"}, {"1/(2 ln2)", "0.72"}}), "a 1 b 0.72.");
  EXPECT_EQ(fill("no placeholder {x}", {}), "no placeholder {x}");
  EXPECT_THROW(fill("${z}", {{"x", "1"}}), std::logic_error);
  EXPECT_THROW(fill("${unterminated", {}), std::logic_error);
  ShaderSource without_pi;
  EXPECT_THROW(without_pi.add_file("common/pi.glsl"), std::logic_error);
  EXPECT_THROW(without_pi.add_file("lobes/no-such-family.glsl"), std::logic_error);
  EXPECT_NE(find_shader_file("lobes/log.glsl"), nullptr);
  EXPECT_EQ(find_shader_file("lobes/log"), nullptr);
}

}  // namespace
}  // namespace specula::glsl
