// The GL renderer against the CPU renderer (include/specula/gl/render_gl.h): the same 8-bit image
// (within 1/255 in >= 99.9 % of the pixels) for many models, a mesh with shadows and spheres
// shadowing each other; the same linear values at chosen pixels; the display transform in the
// shader; tiles; bad input.
#include "specula/catalogue/catalogue.h"
#include "specula/gl/render_gl.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <unistd.h>

#include "gl_support.h"
#include "specula/exceptions.h"
#include "specula/render/scene_shader.h"

namespace specula::gl {
namespace {

using ::testing::HasSubstr;
using specula::testing::shared_context;

Renderer& shared_renderer() {
  static Renderer renderer(shared_context());
  return renderer;
}

render::Scene three_light_scene(const Model& model) {
  render::Scene scene = render::default_scene(model);
  scene.lights = {render::Light{.direction = {-1, 1, 1}}, render::Light{.direction = {1, 0.5, 1}},
                  render::Light{.kind = render::LightKind::point, .position = {0, 3, 3}}};
  return scene;
}

struct Agreement {
  double within_one = 0;  ///< fraction of pixels whose three 8-bit codes differ by at most 1
  double identical = 0;   ///< fraction of pixels with the same three codes
  int max_difference = 0;
};

Agreement agreement(const render::Image& cpu, const render::Image& gl, const render::Display& display = {}) {
  const auto a = render::to_srgb8(cpu, display), b = render::to_srgb8(gl, display);
  Agreement result;
  const std::size_t pixels = a.size() / 3;
  for (std::size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (std::size_t c = 3 * p; c < 3 * p + 3; ++c) worst = std::max(worst, std::abs(int(a[c]) - int(b[c])));
    result.within_one += worst <= 1;
    result.identical += worst == 0;
    result.max_difference = std::max(result.max_difference, worst);
  }
  result.within_one /= static_cast<double>(pixels);
  result.identical /= static_cast<double>(pixels);
  return result;
}

// Renders `scene` on both backends, prints the agreement and checks the 99.9 % bar.
Agreement expect_agreement(const render::Scene& scene, const std::string& label, int size = 256) {
  const render::Image cpu = render::render_cpu(scene, {size, size});
  const render::Image gl = shared_renderer().render(scene, {size, size});
  const Agreement a = agreement(cpu, gl);
  const auto codes = render::to_srgb8(cpu, {});
  const auto lit = std::count_if(codes.begin(), codes.end(), [](std::uint8_t c) { return c > 8; });
  EXPECT_GT(lit, static_cast<long>(codes.size() / 10)) << label << ": too dark to compare";
  std::cout << fmt::format("[ agree    ] {:<32} {:7.3f} % within 1/255, {:7.3f} % identical, max {}/255\n", label,
                           100 * a.within_one, 100 * a.identical, a.max_difference);
  EXPECT_GE(a.within_one, 0.999) << label;
  return a;
}

Model model_at_n50(std::string_view id) {
  const ModelInfo* info = find_model(id);
  return info->find_param("n") ? make_model(id, {{"n", 50}}) : make_model(id);
}

TEST(RenderGl, AgreesWithTheCpuOnTheSphereForEveryModel) {
  for (const auto& info : models()) {
    SCOPED_TRACE(std::string(info.id));
    const Model model = model_at_n50(info.id);
    expect_agreement(three_light_scene(model), fmt::format("sphere, {} {}", info.id, info.find_param("n") ? "n=50" : "defaults"));
  }
}

TEST(RenderGl, AgreesWithTheCpuInTheOtherForm) {
  expect_agreement(three_light_scene(make_model("log-normalized", {{"n", 50}}, Form::nh)), "sphere, log-normalized nh");
  expect_agreement(three_light_scene(make_model("phong", {{"n", 200}}).with_coef(3)), "sphere, phong n=200 k=3");
}

// The default sphere under the three lights: a wide sample of values, to be within float's reach
// of the double renderer.
TEST(RenderGl, LinearValuesMatchTheCpuAtChosenPixels) {
  const render::Scene scene = three_light_scene(make_model("log-normalized", {{"n", 50}}));
  const render::Image cpu = render::render_cpu(scene, {256, 256});
  const render::Image gl = shared_renderer().render(scene, {256, 256});
  int brightest_x = 0, brightest_y = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x)
      if (cpu.at(x, y).g > cpu.at(brightest_x, brightest_y).g) brightest_x = x, brightest_y = y;
  const std::pair<int, int> pixels[] = {{128, 128}, {brightest_x, brightest_y}, {60, 80}, {200, 150}, {128, 40},
                                        {90, 200},  {0, 0}};
  for (const auto& [x, y] : pixels) {
    const render::Rgb c = cpu.at(x, y), g = gl.at(x, y);
    std::cout << fmt::format("[ linear   ] pixel {:3},{:3}: cpu {:.7g} {:.7g} {:.7g}, gl {:.7g} {:.7g} {:.7g}\n", x, y,
                             c.r, c.g, c.b, g.r, g.g, g.b);
    for (const auto& [cv, gv] : {std::pair{c.r, g.r}, {c.g, g.g}, {c.b, g.b}})
      EXPECT_NEAR(gv, cv, 1e-4 * std::max(1.0, cv)) << x << "," << y;
  }
  EXPECT_GT(cpu.at(brightest_x, brightest_y).g, 1.0);  // the highlight, not a dull pixel
  EXPECT_EQ(gl.at(0, 0), (render::Rgb{0, 0, 0}));      // the background
}

void add_box(std::vector<render::Triangle>& mesh, Vec3 lo, Vec3 hi) {
  const Vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                     {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}};
  for (const auto& f : faces) {
    mesh.push_back({{c[f[0]], c[f[1]], c[f[2]]}, {}, false});
    mesh.push_back({{c[f[0]], c[f[2]], c[f[3]]}, {}, false});
  }
}

// An icosahedron subdivided `levels` times onto a sphere, with vertex normals (smooth shading).
void add_icosphere(std::vector<render::Triangle>& mesh, Vec3 centre, double radius, int levels) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  const Vec3 v[12] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                        {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  std::vector<std::array<Vec3, 3>> faces;
  for (const auto& face : f) faces.push_back({normalized(v[face[0]]), normalized(v[face[1]]), normalized(v[face[2]])});
  for (int level = 0; level < levels; ++level) {
    std::vector<std::array<Vec3, 3>> finer;
    for (const auto& [a, b, c] : faces) {
      const Vec3 ab = normalized(a + b), bc = normalized(b + c), ca = normalized(c + a);
      finer.insert(finer.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
    }
    faces = std::move(finer);
  }
  for (const auto& [a, b, c] : faces)
    mesh.push_back({{centre + a * radius, centre + b * radius, centre + c * radius}, {a, b, c}, true});
}

// A floor, a box and a smooth icosphere above it: shadows of flat and curved triangles.
render::Scene mesh_scene(Model model) {
  render::Scene scene = three_light_scene(std::move(model));
  scene.spheres.clear();
  add_box(scene.triangles, {-3, -1.2, -3}, {3, -1, 3});
  add_box(scene.triangles, {-1.4, -1, -0.4}, {-0.4, 0, 0.6});
  add_icosphere(scene.triangles, {0.8, -0.2, 0.2}, 0.7, 3);
  scene.camera = {{0.5, 3, 5}, {0, -0.6, 0}, {0, 1, 0}, 45};
  return scene;
}

TEST(RenderGl, AgreesWithTheCpuOnAMeshWithShadows) {
  const render::Scene scene = mesh_scene(make_model("log-normalized", {{"n", 50}}));
  expect_agreement(scene, fmt::format("mesh ({} triangles), log-normalized", scene.triangles.size()));
  expect_agreement(mesh_scene(make_model("ggx")), "mesh, ggx");
  // The shadow is there on both: the floor behind the box (from the dir:-1,1,1 light) is darker.
  const render::Image gl = shared_renderer().render(scene, {256, 256});
  const render::Image cpu = render::render_cpu(scene, {256, 256});
  int shadowed = 0;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) shadowed += cpu.at(x, y).r < 0.05 && cpu.at(x, y).r > 0 && gl.at(x, y).r < 0.05;
  EXPECT_GT(shadowed, 200);
}

TEST(RenderGl, AgreesWithTheCpuOnAMeshReadFromAnObjFile) {
  const auto path = std::filesystem::temp_directory_path() / fmt::format("specula-gl-test-{}.obj", ::getpid());
  std::string obj;
  std::vector<render::Triangle> mesh;
  add_icosphere(mesh, {0, 0, 0}, 1, 2);
  add_box(mesh, {-2, -1.5, -2}, {2, -1.2, 2});
  for (const auto& t : mesh)
    for (const Vec3& p : t.vertices) obj += fmt::format("v {} {} {}\n", p.x, p.y, p.z);
  for (std::size_t i = 0; i < mesh.size(); ++i) obj += fmt::format("f {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
  std::ofstream(path) << obj;
  render::Scene scene = three_light_scene(make_model("blinn-phong-normalized", {{"n", 50}}));
  scene.spheres.clear();
  scene.triangles = render::load_obj(path);
  std::filesystem::remove(path);
  scene.camera = render::framing(scene.triangles);
  expect_agreement(scene, "OBJ, flat-shaded icosphere on a slab");
}

TEST(RenderGl, AgreesWithTheCpuOnSpheresShadowingEachOther) {
  render::Scene scene = three_light_scene(make_model("schlick", {{"n", 50}}));
  scene.spheres = {{{0, -101, 0}, 100}, {{-0.6, 0, 0}, 0.6}, {{0.7, -0.4, 0.5}, 0.4}};
  scene.background = {0.1, 0.2, 0.3};
  expect_agreement(scene, "three spheres, schlick");
  // The same through the shader that also traverses a mesh: one triangle buried in the floor.
  scene.triangles.push_back({{Vec3{0, -150, 0}, Vec3{1, -150, 0}, Vec3{0, -150, 1}}, {}, false});
  ASSERT_EQ(render::geometry_of(scene), render::SceneGeometry::spheres_and_mesh);
  expect_agreement(scene, "three spheres + buried triangle");
}

TEST(RenderGl, TheShadersDisplayTransformMatchesToSrgb8) {
  const render::Scene scene = three_light_scene(make_model("ward"));
  const render::Display display{0.5, render::ToneMap::aces};
  const auto cpu = render::to_srgb8(render::render_cpu(scene, {128, 128}), display);
  const render::Image shown = shared_renderer().render(scene, {128, 128}, display);
  int within_one = 0;
  const auto samples = shown.samples();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    ASSERT_GE(samples[i], 0.0f);
    ASSERT_LE(samples[i], 1.0f);
    within_one += std::abs(std::lround(255 * samples[i]) - long(cpu[i])) <= 1;
  }
  EXPECT_GE(within_one, 0.999 * static_cast<double>(samples.size()));
}

TEST(RenderGl, TilesGiveTheSameImage) {
  const render::Scene scene = mesh_scene(make_model("phong-normalized", {{"n", 50}}));
  Renderer tiled(shared_context(), 50);
  const render::Image whole = shared_renderer().render(scene, {130, 120});
  const render::Image pieces = tiled.render(scene, {130, 120});
  EXPECT_TRUE(std::equal(whole.samples().begin(), whole.samples().end(), pieces.samples().begin()));
}

TEST(RenderGl, CompilesOncePerModel) {
  Renderer renderer(shared_context());
  const Model model = make_model("gauss", {{"n", 20}});
  constexpr auto spheres = render::SceneGeometry::spheres;
  EXPECT_GT(renderer.prepare(model, spheres), 0.0);
  EXPECT_EQ(renderer.prepare(model, spheres), 0.0);
  EXPECT_EQ(renderer.prepare(make_model("gauss", {{"n", 30}}), spheres), 0.0);  // a parameter is a uniform
  EXPECT_GT(renderer.prepare(make_model("gauss", {{"n", 30}}, Form::rv), spheres), 0.0);  // the default is nh
  EXPECT_GT(renderer.prepare(make_model("gauss", {{"n", 30}}, Form::rv), render::SceneGeometry::spheres_and_mesh), 0.0);
}

std::string error_of(const render::Scene& scene, const render::RenderSettings& settings) {
  try {
    render_gl(scene, settings);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

TEST(RenderGl, BadInputGivesOneClearLine) {
  render::Scene scene = render::default_scene(make_model("phong"));
  scene.lights.assign(9, render::Light{});
  EXPECT_EQ(error_of(scene, {8, 8}), "the GL renderer takes at most 8 lights; the scene has 9");
  scene.lights = {render::Light{}};
  scene.spheres.assign(17, render::Sphere{});
  EXPECT_EQ(error_of(scene, {8, 8}), "the GL renderer draws at most 16 spheres; the scene has 17");
  scene.spheres = {render::Sphere{}};
  EXPECT_THAT(error_of(scene, {8, 0}), HasSubstr("image size 8x0 is invalid"));
  scene.camera.vertical_fov_deg = 180;
  EXPECT_THAT(error_of(scene, {8, 8}), HasSubstr("field of view"));
}

TEST(RenderGl, RenderGlMakesItsOwnContext) {
  const render::Image image = render_gl(render::default_scene(make_model("ggx")), {16, 16});
  EXPECT_GT(image.at(8, 8).r, 0.0f);
  shared_context().make_current();
}

}  // namespace
}  // namespace specula::gl
