// The scene shader's text and values (include/specula/render/scene_shader.h): every shader accepted by
// glslangValidator for every model and dialect, ASCII and cited, the uniforms documented; the
// uniform values and mesh textures laid out as the shader reads them; the limits.
#include "specula/catalogue/catalogue.h"
#include "specula/render/scene_shader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <set>

#include "glsl_support.h"
#include "specula/exceptions.h"
#include "text_support.h"

namespace specula::render {
namespace {

using ::testing::HasSubstr;

constexpr glsl::Dialect kDialects[] = {glsl::Dialect::glsl330, glsl::Dialect::gles300, glsl::Dialect::webgl2};

TEST(SceneShader, EveryModelsShadersPassGlslangInEveryDialect) {
  for (const glsl::Dialect dialect : kDialects) {
    const auto vertex = testing::validate_glsl(scene_vertex_shader(dialect), "vert");
    EXPECT_TRUE(vertex.ok) << to_string(dialect) << "\n" << vertex.log;
    const auto spheres = testing::validate_glsl(
        scene_fragment_shader(make_model("log-normalized"), dialect, SceneGeometry::spheres), "frag");
    EXPECT_TRUE(spheres.ok) << "spheres only, " << to_string(dialect) << "\n" << spheres.log;
    for (const auto& info : models()) {
      const auto fragment = testing::validate_glsl(scene_fragment_shader(make_model(info.id), dialect), "frag");
      EXPECT_TRUE(fragment.ok) << info.id << " " << to_string(dialect) << "\n" << fragment.log;
    }
  }
}

TEST(SceneShader, TheGeometryIsOneDefineAViewerCanOverride) {
  const std::string mesh = scene_fragment_shader(make_model("ggx"), glsl::Dialect::glsl330);
  const std::string spheres = scene_fragment_shader(make_model("ggx"), glsl::Dialect::glsl330, SceneGeometry::spheres);
  EXPECT_THAT(mesh, HasSubstr("#ifndef SCENE_MESH\n#define SCENE_MESH 1\n#endif"));
  EXPECT_THAT(spheres, HasSubstr("#ifndef SCENE_MESH\n#define SCENE_MESH 0\n#endif"));
  EXPECT_EQ(std::regex_replace(spheres, std::regex("#define SCENE_MESH 0"), "#define SCENE_MESH 1"), mesh);
  Scene scene = default_scene(make_model("ggx"));
  EXPECT_EQ(geometry_of(scene), SceneGeometry::spheres);
  scene.triangles.push_back({});
  EXPECT_EQ(geometry_of(scene), SceneGeometry::spheres_and_mesh);
}

TEST(SceneShader, GlslangRejectsTheShaderWithAPieceMissing) {
  const std::string shader = scene_fragment_shader(make_model("ggx"), glsl::Dialect::gles300);
  const std::string no_offset = std::regex_replace(shader, std::regex("uniform vec2 u_pixel_offset;"), "");
  EXPECT_FALSE(testing::validate_glsl(no_offset, "frag").ok);
}

TEST(SceneShader, AsciiOnlyAndEveryFunctionCitedOnItsFirstLine) {
  const std::regex definition(R"(^(float|bool|vec3|vec4|void|SceneSurface) (\w+)\(.*\) \{$)");
  const std::string shader = scene_fragment_shader(make_model("log-normalized", {{"n", 50}}), glsl::Dialect::glsl330);
  for (const char ch : shader) ASSERT_LT(static_cast<unsigned char>(ch), 0x80);
  const auto lines = testing::lines_of(shader);
  std::set<std::string> functions;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::smatch match;
    if (!std::regex_match(lines[i], match, definition)) continue;
    functions.insert(match[2]);
    EXPECT_EQ(lines[i - 1].rfind("// ", 0), 0u) << match[2] << " has no citation";
  }
  for (const char* name : {"scene_sphere_hit", "scene_triangle_hit", "scene_mesh_hit", "scene_offset_ray",
                           "scene_surface_radiance", "scene_display", "main", "specula_brdf"})
    EXPECT_TRUE(functions.contains(name)) << name;
  EXPECT_THAT(shader, HasSubstr("Haines et al. 2019"));
  EXPECT_THAT(shader, HasSubstr("Wachter & Binder 2019"));
}

TEST(SceneShader, DocumentsEveryUniformWithTheDefaultScenesValue) {
  const std::string shader = scene_fragment_shader(make_model("phong"), glsl::Dialect::webgl2);
  const std::regex declaration(R"(^uniform (highp )?(\w+) (\w+)(\[\w+\])?;$)");
  int uniforms = 0;
  for (const std::string& line : testing::lines_of(shader)) {
    std::smatch match;
    if (!std::regex_match(line, match, declaration)) continue;
    ++uniforms;
    const std::string name = match[3];
    EXPECT_THAT(shader, HasSubstr(fmt::format("//   {} {}", std::string(match[2]), name + (match[4].matched ? "[]" : ""))))
        << name << " is not documented";
  }
  EXPECT_EQ(uniforms, 22);
  // The default camera and light, as scene_uniforms computes them.
  EXPECT_THAT(shader, HasSubstr("whole image, pixels [512, 512]"));
  EXPECT_THAT(shader, HasSubstr("toward the light; w 1: position [-0.57735, 0.57735, 0.57735, 0]"));
  EXPECT_THAT(shader, HasSubstr("camera position [0, 0, 3.8"));
}

// The names are written once, in scene_uniform: the shader declares exactly those, in that order,
// and SceneUniforms::visit passes every one but the samplers, in the same order.
TEST(SceneShader, DeclaresTheUniformsOfTheOneListAndVisitPassesThem) {
  const std::string shader = scene_fragment_shader(make_model("ggx"), glsl::Dialect::webgl2);
  const std::regex declaration(R"(^uniform (highp )?(\w+) (\w+)(\[\w+\])?;$)");
  std::vector<std::string> declared;
  for (const std::string& line : testing::lines_of(shader)) {
    std::smatch match;
    if (std::regex_match(line, match, declaration)) declared.push_back(match[3]);
  }
  std::vector<std::string> listed, visited;
  for (const SceneUniform& u : scene_uniform::all) listed.emplace_back(u.name);
  EXPECT_EQ(declared, listed);
  EXPECT_THAT(shader, HasSubstr("uniform vec4 u_spheres[SCENE_MAX_SPHERES];\n"));
  EXPECT_THAT(shader, HasSubstr("uniform highp sampler2D u_bvh;\n"));
  const SceneUniforms u = scene_uniforms(default_scene(make_model("ggx")), {8, 8});
  u.visit([&](const SceneUniform& uniform, const auto&) { visited.emplace_back(uniform.name); });
  std::erase_if(listed, [](const std::string& name) {
    return name == scene_uniform::triangles.name || name == scene_uniform::bvh.name;
  });
  EXPECT_EQ(visited, listed);
}

TEST(SceneUniforms, CameraLightsAndMaterialAsPinholeRaysAndTheShaderNeedThem) {
  Scene scene = default_scene(make_model("schlick-modified", {{"n", 7}, {"s", 2}}));
  scene.camera = {{1, 2, 3}, {1, 2, 0}, {0, 1, 0}, 90};
  scene.lights = {Light{.direction = {0, 0, 2}, .colour = {1, 0.5, 0.25}, .intensity = 2},
                  Light{.kind = LightKind::point, .position = {1, 2, 3}, .intensity = 9}};
  scene.spheres.push_back({{1, 1, 1}, 0.5});
  const SceneUniforms u = scene_uniforms(scene, {200, 100}, Display{1.5, ToneMap::aces});
  EXPECT_EQ(u.resolution, (std::array<float, 2>{200, 100}));
  EXPECT_EQ(u.eye, (std::array<float, 3>{1, 2, 3}));
  EXPECT_EQ(u.forward, (std::array<float, 3>{0, 0, -1}));
  EXPECT_NEAR(u.right[0], 2.0, 1e-6);  // tan 45° · aspect 2
  EXPECT_NEAR(u.up[1], 1.0, 1e-6);
  ASSERT_EQ(u.spheres.size(), 2u);
  EXPECT_EQ(u.spheres[1], (std::array<float, 4>{1, 1, 1, 0.5}));
  EXPECT_EQ(u.lights[0], (std::array<float, 4>{0, 0, 1, 0}));
  EXPECT_EQ(u.lights[1], (std::array<float, 4>{1, 2, 3, 1}));
  EXPECT_EQ(u.light_irradiance[0], (std::array<float, 3>{2, 1, 0.5}));
  EXPECT_EQ(u.model_params, (std::array<float, 4>{7, 2, 0, 0}));
  EXPECT_EQ(u.diffuse, (std::array<float, 3>{0.55f, 0.12f, 0.1f}));
  EXPECT_EQ(u.display, 1);
  EXPECT_EQ(u.exposure, 1.5f);
  EXPECT_EQ(u.tone_map, 1);
  EXPECT_EQ(scene_uniforms(scene, {1, 1}).display, 0);
}

std::string error_of(const Scene& scene, const RenderSettings& settings) {
  try {
    scene_uniforms(scene, settings);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

TEST(SceneUniforms, RefusesWhatTheShaderCannotHoldAndWhatRenderCpuRefuses) {
  Scene scene = default_scene(make_model("phong"));
  scene.spheres.assign(kShaderMaxSpheres, Sphere{});
  EXPECT_EQ(error_of(scene, {8, 8}), "no error");
  scene.spheres.push_back({});
  EXPECT_EQ(error_of(scene, {8, 8}), "the GL renderer draws at most 16 spheres; the scene has 17");
  scene.spheres = {Sphere{}};
  scene.lights.assign(kShaderMaxLights + 1, Light{});
  EXPECT_EQ(error_of(scene, {8, 8}), "the GL renderer takes at most 8 lights; the scene has 9");
  scene.lights = {Light{}};
  EXPECT_THAT(error_of(scene, {0, 8}), HasSubstr("image size 0x8 is invalid"));
  EXPECT_THAT(error_of(scene, {8, kMaxImageSide + 1}), HasSubstr("is invalid"));
  scene.spheres[0].radius = -1;
  EXPECT_THAT(error_of(scene, {8, 8}), HasSubstr("radius"));
}

Triangle triangle(Vec3 a, Vec3 b, Vec3 c) {
  return {{a, b, c}, {Vec3{0, 0, 1}, Vec3{0, 1, 0}, Vec3{1, 0, 0}}, true};
}

TEST(MeshTextures, TrianglesInLeafOrderAndNodesAsTheShaderReadsThem) {
  std::vector<Triangle> soup;
  for (int i = 0; i < 9; ++i) soup.push_back(triangle({0.1 * i, 0, 0}, {0.1 * i + 1, 0, 0}, {0.1 * i, 1, 1.0 / 3}));
  soup[4].has_normals = false;
  const Bvh bvh(soup);
  const MeshTextures mesh = mesh_textures(bvh, 7);
  EXPECT_EQ(mesh.width, 7);
  EXPECT_EQ(mesh.triangle_rows, 8);  // 54 texels in rows of 7
  EXPECT_EQ(mesh.triangles.size(), 4u * 7 * 8);
  EXPECT_EQ(mesh.node_rows, static_cast<int>((2 * bvh.node_count() + 6) / 7));
  for (std::size_t i = 0; i < bvh.size(); ++i) {
    const Triangle& t = bvh.triangles()[i];
    const float* texels = &mesh.triangles[24 * i];
    EXPECT_EQ(texels[0], static_cast<float>(t.vertices[0].x));
    EXPECT_EQ(texels[3], t.has_normals ? 1.0f : 0.0f);
    EXPECT_EQ(texels[4], static_cast<float>(t.vertices[1].x - t.vertices[0].x));   // e1
    EXPECT_EQ(texels[10], static_cast<float>(t.vertices[2].z - t.vertices[0].z));  // e2.z
    EXPECT_EQ(texels[13], static_cast<float>(t.normals[0].y));                      // n0.y
  }
  for (std::size_t i = 0; i < bvh.node_count(); ++i) {
    const Bvh::Node& node = bvh.nodes()[i];
    const float* texels = &mesh.nodes[8 * i];
    EXPECT_LE(texels[2], node.box.min.z);  // rounded outward: 1/3 is not a float
    EXPECT_GE(texels[6], node.box.max.z);
    EXPECT_LT(texels[2], texels[6]);
    EXPECT_EQ(texels[3], static_cast<float>(node.first));
    EXPECT_EQ(texels[7], static_cast<float>(node.count));
  }
  EXPECT_THROW(mesh_textures(bvh, 0), InvalidArgument);
}

TEST(MeshTextures, AnEmptyMeshIsOneRowOfZeros) {
  const MeshTextures mesh = mesh_textures(Bvh({}), 16);
  EXPECT_EQ(mesh.triangle_rows, 1);
  EXPECT_EQ(mesh.node_rows, 1);
  EXPECT_EQ(mesh.nodes, std::vector<float>(64, 0.0f));
}

}  // namespace
}  // namespace specula::render
