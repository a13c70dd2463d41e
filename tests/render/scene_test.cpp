// Scenes (include/specula/render/scene.h, bvh.h): lights, scenes from typed descriptions, the
// material, OBJ loading, validation, and the BVH against brute force.
#include "specula/catalogue/catalogue.h"
#include "specula/render/scene.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "render_support.h"
#include "specula/exceptions.h"
#include "specula/render/bvh.h"

namespace specula::render {
namespace {

using ::testing::HasSubstr;
using specula::testing::TempDir;

// The render library takes typed values: a light is built, not parsed (the CLI's --light syntax
// is read in apps/specula/scene_options.cpp, tested in tests/cli/scene_options_test.cpp).
TEST(Light, ToStringWritesEveryPart) {
  EXPECT_EQ(to_string(Light{}), "dir:-1,1,1:1,1,1:1");
  const Light p{.kind = LightKind::point, .position = {-1, 0.5, 4}, .colour = {1, 0.9, 0.8}, .intensity = 25};
  EXPECT_EQ(to_string(p), "point:-1,0.5,4:1,0.9,0.8:25");
}

TEST(CheckLight, NamesTheLightAndWhatIsWrong) {
  const auto error_of = [](const Light& light) -> std::string {
    try {
      check_light(light, "the lamp");
    } catch (const InvalidArgument& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(error_of(Light{}), "no error");
  EXPECT_EQ(error_of(Light{.direction = {0, 0, 0}}), "the lamp: the direction must be finite and non-zero");
  EXPECT_EQ(error_of(Light{.kind = LightKind::point, .position = {0, 0, 0}}), "no error");
  EXPECT_EQ(error_of(Light{.kind = LightKind::point, .position = {0, std::nan(""), 0}}),
            "the lamp: the direction must be finite and non-zero");
  EXPECT_EQ(error_of(Light{.colour = {-1, 1, 1}}), "the lamp: colour and intensity must be finite and ≥ 0");
  EXPECT_EQ(error_of(Light{.intensity = INFINITY}), "the lamp: colour and intensity must be finite and ≥ 0");
}

bool same(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

TEST(MakeScene, IsTheDefaultSceneWithWhatTheDescriptionChooses) {
  const Model model = make_model("phong");
  const Scene plain = make_scene(model, {});
  const Scene reference = default_scene(model);
  EXPECT_EQ(to_string(plain.lights.at(0)), to_string(reference.lights.at(0)));
  EXPECT_EQ(plain.spheres.size(), 1u);
  EXPECT_TRUE(same(plain.camera.position, reference.camera.position));
  EXPECT_EQ(plain.material.diffuse, reference.material.diffuse);
  EXPECT_EQ(plain.material.ambient, reference.material.ambient);

  const Light point{.kind = LightKind::point, .position = {1, 2, 3}, .intensity = 9};
  const Scene chosen = make_scene(model, {.lights = std::vector<Light>{point, Light{}},
                                          .diffuse = Rgb{0.1, 0.2, 0.3},
                                          .specular = std::nullopt,
                                          .ambient = Rgb{0, 0, 0}});
  ASSERT_EQ(chosen.lights.size(), 2u);
  EXPECT_EQ(to_string(chosen.lights[0]), "point:1,2,3:1,1,1:9");
  EXPECT_EQ(chosen.material.diffuse, (Rgb{0.1, 0.2, 0.3}));
  EXPECT_EQ(chosen.material.specular, reference.material.specular);
  EXPECT_EQ(chosen.material.ambient, (Rgb{0, 0, 0}));
  EXPECT_TRUE(make_scene(model, {.lights = std::vector<Light>{}}).lights.empty());

  std::vector<Triangle> mesh(1);
  mesh[0].vertices = {Vec3{0, 0, 0}, Vec3{2, 0, 0}, Vec3{0, 2, 0}};
  const Scene meshed = make_scene(model, {.mesh = mesh});
  EXPECT_TRUE(meshed.spheres.empty());
  EXPECT_EQ(meshed.triangles.size(), 1u);
  EXPECT_TRUE(same(meshed.camera.look_at, framing(mesh).look_at));
  EXPECT_TRUE(same(meshed.camera.position, framing(mesh).position));
}

TEST(Material, ItsBrdfIsDiffuseOverPiPlusSpecularTimesFAndItsAmbientTermAmbientTimesDiffuse) {
  Material m(make_model("phong"));
  m.diffuse = {0.5, 0.25, 1};
  m.specular = {1, 2, 4};
  m.ambient = {0.1, 0.2, 0.4};
  const Rgb brdf = m.brdf(0.5);
  EXPECT_DOUBLE_EQ(brdf.r, 0.5 / M_PI + 0.5);
  EXPECT_DOUBLE_EQ(brdf.g, 0.25 / M_PI + 1);
  EXPECT_DOUBLE_EQ(brdf.b, 1 / M_PI + 2);
  EXPECT_EQ(m.brdf(0), m.diffuse * (1 / M_PI));
  EXPECT_EQ(m.ambient_radiance(), (Rgb{0.05, 0.05, 0.4}));
}

constexpr const char* kTetrahedron =
    "# a tetrahedron, one face a quad split in two\n"
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
    "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";

TEST(LoadObj, ReadsEveryFaceAsTriangles) {
  TempDir dir;
  const auto triangles = load_obj(dir.write("t.obj", kTetrahedron));
  ASSERT_EQ(triangles.size(), 4u);
  EXPECT_EQ(triangles[1].vertices[2].z, 1);
  EXPECT_FALSE(triangles[0].has_normals);
}

TEST(LoadObj, SplitsPolygonsAndKeepsUnitVertexNormals) {
  TempDir dir;
  const auto triangles = load_obj(dir.write("quad.obj",
      "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 2\nf 1//1 2//1 3//1 4//1\n"));
  ASSERT_EQ(triangles.size(), 2u);
  EXPECT_TRUE(triangles[0].has_normals);
  EXPECT_EQ(triangles[1].normals[2].z, 1);
}

TEST(LoadObj, FailsInOneLineNamingTheFile) {
  TempDir dir;
  const auto expect_error = [](const std::filesystem::path& path, const std::string& what) {
    try {
      load_obj(path);
      ADD_FAILURE() << path << " loaded";
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr("cannot read '" + path.string() + "': " + what));
      EXPECT_THAT(std::string(e.what()), ::testing::Not(HasSubstr("\n")));
    }
  };
  expect_error(dir / "missing.obj", "No such file or directory");
  expect_error(dir.path(), "it is a directory");
  expect_error(dir.write("empty.obj", ""), "no triangles");
  expect_error(dir.write("lines.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n"), "no triangles");
  expect_error(dir.write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"), "a face refers to vertex 9");
  expect_error(dir.write("normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n"), "a face refers to normal 4");
}

TEST(Framing, FitsTheBoundingSphereInTheVerticalFieldOfView) {
  const Camera c = framing(Vec3{1, 2, 3}, 2, 40);
  EXPECT_EQ(c.look_at.x, 1);
  EXPECT_NEAR(c.position.z - 3, 1.15 * 2 / std::sin(20 * std::numbers::pi / 180), 1e-12);
  TempDir dir;
  const Camera t = framing(load_obj(dir.write("t.obj", kTetrahedron)));
  EXPECT_EQ(t.look_at.x, 0.5);
  EXPECT_EQ(t.vertical_fov_deg, 35);
}

TEST(Validate, NamesTheInvalidPart) {
  const auto expect_error = [](const Scene& scene, const std::string& what) {
    try {
      validate(scene);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr(what));
    }
  };
  const Scene good = default_scene(make_model("phong"));
  EXPECT_NO_THROW(validate(good));
  Scene s = good;
  s.camera.look_at = s.camera.position;
  expect_error(s, "camera");
  s = good;
  s.camera.up = {0, 0, -2};
  expect_error(s, "up vector");
  s = good;
  s.camera.vertical_fov_deg = 180;
  expect_error(s, "field of view");
  s = good;
  s.spheres[0].radius = 0;
  expect_error(s, "radius");
  s = good;
  s.lights[0].intensity = -1;
  expect_error(s, "light 1");
  s = good;
  s.material.diffuse.g = std::nan("");
  expect_error(s, "colours");
}

// The BVH finds exactly what testing every triangle finds: the same nearest t, the same answer
// to "is anything in the way".
Vec3 random_point(double scale) {
  const auto coordinate = [&] { return *rc::gen::inRange(-1000, 1001) * scale / 1000; };
  return {coordinate(), coordinate(), coordinate()};
}

std::optional<TriangleHit> brute_force(const std::vector<Triangle>& triangles, const Ray& ray, double t_max) {
  std::optional<TriangleHit> best;
  for (const Triangle& t : triangles)
    if (const auto hit = intersect(ray, t, 0, best ? best->t : t_max)) best = hit;
  return best;
}

RC_GTEST_PROP(BvhProperty, AgreesWithBruteForce, ()) {
  const std::size_t count = *rc::gen::inRange<std::size_t>(1, 300);
  std::vector<Triangle> triangles(count);
  for (Triangle& t : triangles) {
    const Vec3 centre = random_point(5);
    for (Vec3& v : t.vertices) v = centre + random_point(0.7);
  }
  const Bvh bvh(triangles);
  RC_ASSERT(bvh.size() == count);
  RC_ASSERT(bvh.depth() <= static_cast<std::size_t>(std::ceil(std::log2(count / 4.0 + 1))) + 1);
  for (int i = 0; i < 20; ++i) {
    const Vec3 origin = random_point(8);
    const Vec3 target = random_point(4);
    const Ray ray{origin, normalized(target - origin)};
    const double t_max = *rc::gen::element(5.0, 10.0, std::numeric_limits<double>::infinity());
    const auto expected = brute_force(triangles, ray, t_max);
    const auto found = bvh.closest(ray, 0, t_max);
    RC_ASSERT(found.has_value() == expected.has_value());
    if (found) RC_ASSERT(found->t == expected->t);
    RC_ASSERT(bvh.occluded(ray, 0, t_max) == expected.has_value());
  }
}

TEST(Bvh, HitsAxisAlignedRaysAndEmptyTreesFindNothing) {
  TempDir dir;
  const Bvh bvh(load_obj(dir.write("t.obj", kTetrahedron)));
  const auto hit = bvh.closest({{0.2, 0.2, 5}, {0, 0, -1}});
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 5 - 0.6);  // the face x + y + z = 1
  EXPECT_FALSE(bvh.closest({{2, 2, 5}, {0, 0, -1}}));
  EXPECT_FALSE(Bvh({}).closest({{0, 0, 5}, {0, 0, -1}}));
  EXPECT_FALSE(Bvh({}).occluded({{0, 0, 5}, {0, 0, -1}}, 0, 10));
}

}  // namespace
}  // namespace specula::render
