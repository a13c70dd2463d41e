// The CPU renderer (include/specula/render/render.h): every pixel against shading computed by hand,
// energy bounds, bit-identical images for any thread count, meshes and their shadows, bad input.
#include "specula/catalogue/catalogue.h"
#include "specula/render/render.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <string>

#include "render_support.h"
#include "specula/exceptions.h"

namespace specula::render {
namespace {

using ::testing::HasSubstr;
using specula::testing::pixel_ray;
using specula::testing::TempDir;
using specula::testing::unit;

constexpr double kPiRadians = std::numbers::pi;
// coef(20) of the log lobe in rv form, by mpmath (tests/reference/normalization.csv).
constexpr double kLogCoef20 = 4.1927561168511793081;

// The hand-made side: camera rays (render_support.h), the textbook ray/sphere quadratic, the lobes of
// docs/math.md §2.
std::optional<double> sphere_hit(const Ray& ray, const Sphere& s) {
  const Vec3 f = ray.origin - s.centre;
  const double b = 2 * dot(f, ray.direction), c = dot(f, f) - s.radius * s.radius;
  const double discriminant = b * b - 4 * c;
  if (discriminant < 0) return std::nullopt;
  return (-b - std::sqrt(discriminant)) / 2;
}

struct Lobe {
  double n;
  double k;
  bool log;
  // F(R·V) in rv form: c^n, or max(0, 1 − ½ log₂(1 − n log₂ c)).
  double operator()(double c) const {
    if (c <= 0) return 0;
    c = std::min(c, 1.0);
    return k * (log ? std::max(0.0, 1 - 0.5 * std::log2(1 - n * std::log2(c))) : std::pow(c, n));
  }
};

Rgb expected_radiance(const Scene& scene, const Lobe& lobe, const Ray& ray) {
  const auto t = sphere_hit(ray, scene.spheres[0]);
  if (!t) return scene.background;
  const Vec3 p = ray.origin + ray.direction * *t;
  const Vec3 n = unit(p - scene.spheres[0].centre);
  const Vec3 v = -ray.direction;
  const Material& m = scene.material;
  Rgb sum = m.ambient * m.diffuse;
  for (const Light& light : scene.lights) {
    Vec3 l = light.direction;
    double e = light.intensity;
    if (light.kind == LightKind::point) {
      l = light.position - p;
      e /= dot(l, l);
    }
    l = unit(l);
    const double cos_i = dot(n, l);
    if (cos_i <= 0) continue;
    const Vec3 r = n * (2 * cos_i) - l;
    const double f = lobe(dot(r, v));
    sum = sum + (m.diffuse * (1 / kPiRadians) + m.specular * f) * light.colour * (e * cos_i);
  }
  return sum;
}

Scene analytic_scene(const Model& model) {
  Scene scene = default_scene(model);
  scene.camera = {{0.3, 0.2, 4}, {0, 0, 0}, {0, 1, 0}, 35};
  scene.lights = {{LightKind::directional, {-1, 1, 1.5}, {}, {1, 0.9, 0.8}, 2},
                  {LightKind::point, {}, {2, 1, 3}, {0.7, 0.8, 1}, 20}};
  scene.material.diffuse = {0.5, 0.3, 0.2};
  scene.material.specular = {0.4, 0.5, 0.6};
  scene.material.ambient = {0.05, 0.04, 0.03};
  scene.background = {0.1, 0.2, 0.3};
  return scene;
}

double relative_error(double value, double expected) { return std::abs(value - expected) / std::abs(expected); }

struct ShadedLobe {
  const char* id;
  Lobe lobe;

  friend void PrintTo(const ShadedLobe& s, std::ostream* os) { *os << s.id; }
};

class AnalyticShading : public ::testing::TestWithParam<ShadedLobe> {};

TEST_P(AnalyticShading, EveryPixelMatchesTheHandComputedRadiance) {
  const auto& [id, lobe] = GetParam();
  const Scene scene = analytic_scene(make_model(id, {{"n", 20}}));
  const int width = 96, height = 64;
  const Image image = render_cpu(scene, {width, height});
  int hits = 0, highlights = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Ray ray = pixel_ray(scene.camera, x, y, width, height);
      const Rgb expected = expected_radiance(scene, lobe, ray);
      const Rgb got = image.at(x, y);
      ASSERT_LE(relative_error(got.r, expected.r), 1e-5) << x << "," << y;
      ASSERT_LE(relative_error(got.g, expected.g), 1e-5) << x << "," << y;
      ASSERT_LE(relative_error(got.b, expected.b), 1e-5) << x << "," << y;
      hits += sphere_hit(ray, scene.spheres[0]).has_value();
      highlights += expected.b > 1;  // where the lobe outshines the diffuse term
    }
  EXPECT_GT(hits, width * height / 3);
  EXPECT_GT(highlights, 10);
}

INSTANTIATE_TEST_SUITE_P(Lobes, AnalyticShading,
                         ::testing::Values(ShadedLobe{"phong-normalized", Lobe{20, 22 / (2 * kPiRadians), false}},
                                           ShadedLobe{"log-normalized", Lobe{20, kLogCoef20, true}}),
                         [](const auto& info) {
                           std::string name = info.param.id;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// Energy. A BRDF conserves energy when its albedo ρ(V) = ∫ f(L, V) cos θ_L dω_L ≤ 1 (docs/math.md §1;
// by reciprocity the integral may run over L). Light the sphere from every direction with equal
// radiance L_env = 1 — a "white furnace": M directional lights on a Fibonacci sphere, each with
// E = 4π/M, turn the shading sum into a quadrature of that integral, so each pixel shows
// ρ_d + ρ_s ρ(V) ≤ ρ_d + ρ_s = 1 for a conserving model. The quadrature's own error at M = 4096
// and n = 20 is 4e-6 (measured at the centre pixel, where V = N and ρ(V) = 1 exactly for the
// normalized lobes), hence the 1e-4 tolerance. The bound is on energy, not on the lobe's height:
// a single light's peak E·ρ_s·k, with k ≈ 4, passes 1 easily (OneLightPeaksAt… below).
Scene furnace(const Model& model) {
  Scene scene = default_scene(model);
  scene.material.diffuse = {0.3, 0.3, 0.3};
  scene.material.specular = {0.7, 0.7, 0.7};
  scene.material.ambient = {0, 0, 0};
  scene.lights.clear();
  const int count = 4096;
  const double golden_angle = kPiRadians * (3 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1 - (2 * i + 1.0) / count, s = std::sqrt(1 - z * z);
    scene.lights.push_back({LightKind::directional, {s * std::cos(i * golden_angle), s * std::sin(i * golden_angle), z},
                            {}, {1, 1, 1}, 4 * kPiRadians / count});
  }
  return scene;
}

double max_radiance(const Image& image) {
  return *std::max_element(image.samples().begin(), image.samples().end());
}

TEST(Energy, ConservingLobesStayUnderTheFurnaceBound) {
  for (const auto& model : {make_model("phong-normalized", {{"n", 20}}), make_model("log-normalized", {{"n", 20}}),
                            make_model("ggx", {{"alpha", 0.3}})}) {
    const Image image = render_cpu(furnace(model), {31, 31});
    EXPECT_LE(max_radiance(image), 1 + 1e-4) << model.id();
    if (model.is_lobe()) {
      EXPECT_NEAR(image.at(15, 15).r, 1, 1e-4) << model.id();  // V = N: ρ(V) = 1
    }
  }
}

TEST(Energy, TheFurnaceCatchesLobesThatCreateEnergy) {
  // log-normalized's k used in nh form reflects 3.5× (docs/analysis.md); Cook-Torrance 1982 ~4×.
  for (const auto& model : {make_model("log-normalized", {{"n", 20}}, Form::nh), make_model("cook-torrance-1982")})
    EXPECT_GT(max_radiance(render_cpu(furnace(model), {31, 31})), 1.5) << model.id();
}

TEST(Energy, OneLightPeaksAtTheNormalizedLobesHeight) {
  // Light and camera on the same axis: the centre pixel sees N = L = V, f = k, cos θ_i = 1, so its
  // radiance is E (ρ_d/π + ρ_s k); no pixel exceeds it, since F ≤ 1 and cos θ_i ≤ 1.
  Scene scene = default_scene(make_model("log-normalized", {{"n", 20}}));
  scene.material.ambient = {0, 0, 0};
  scene.lights = {{LightKind::directional, {0, 0, 1}, {}, {1, 1, 1}, 1}};
  const Image image = render_cpu(scene, {33, 33});
  const double peak = 0.4 * kLogCoef20 + 0.55 / kPiRadians;
  EXPECT_LE(max_radiance(image), peak * (1 + 1e-6));
  EXPECT_NEAR(image.at(16, 16).r, peak, peak * 1e-6);
}

Scene busy_scene(const std::filesystem::path& obj) {
  Scene scene = default_scene(make_model("log-normalized", {{"n", 50}}));
  scene.spheres.push_back({{1.2, 0.3, -0.5}, 0.6});
  scene.triangles = load_obj(obj);
  scene.lights.push_back({LightKind::point, {}, {1, 2, 3}, {1, 0.9, 0.8}, 15});
  return scene;
}

constexpr const char* kTetrahedronObj =
    "v -1.5 -1 -1\nv 0.5 -1 -1\nv -1.5 1 -1\nv -1.5 -1 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";

TEST(Determinism, ImagesAreBitIdenticalForAnyThreadCount) {
  TempDir dir;
  const Scene scene = busy_scene(dir.write("t.obj", kTetrahedronObj));
  std::optional<Image> first;
  for (const int threads : {1, 2, 3, 8}) {
    tbb::task_arena arena(threads);
    const Image image = arena.execute([&] { return render_cpu(scene, {67, 45}); });
    if (!first) {
      first = image;
      continue;
    }
    EXPECT_EQ(std::memcmp(image.samples().data(), first->samples().data(), image.samples().size_bytes()), 0)
        << threads << " threads";
  }
}

constexpr const char* kQuad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n";

TEST(Meshes, AnObjQuadIsHitAndShadedLikeAPlane) {
  TempDir dir;
  Scene scene = default_scene(make_model("phong-normalized", {{"n", 20}}));
  scene.spheres.clear();
  scene.triangles = load_obj(dir.write("quad.obj", kQuad));
  scene.camera = framing(scene.triangles);
  scene.lights = {{LightKind::directional, {0.3, 0.2, 1}, {}, {1, 1, 1}, 1}};
  scene.background = {0.5, 0.5, 0.5};
  const Image image = render_cpu(scene, {33, 33});
  // The centre ray meets the quad at the origin: N = V = +z.
  const Vec3 n{0, 0, 1}, l = unit(scene.lights[0].direction);
  const double cos_i = dot(n, l);
  const double f = Lobe{20, 22 / (2 * kPiRadians), false}(dot(n * (2 * cos_i) - l, n));
  const Material& m = scene.material;
  EXPECT_NEAR(image.at(16, 16).r, m.ambient.r * m.diffuse.r + (m.diffuse.r / kPiRadians + m.specular.r * f) * cos_i, 1e-6);
  EXPECT_EQ(image.at(0, 0), scene.background);  // beyond the quad's corner
}

TEST(Meshes, CastShadows) {
  TempDir dir;
  Scene scene = default_scene(make_model("phong-normalized", {{"n", 20}}));
  scene.spheres.clear();
  // A floor quad, and above it a small triangle between the floor point (0.1, 0, 0) and the light.
  scene.triangles = load_obj(dir.write("floor.obj", std::string(kQuad) + "v 0.5 -0.1 0.5\nv 0.7 -0.1 0.5\nv 0.6 0.1 0.5\nf 5 6 7\n"));
  scene.camera = {{0.1, 0, 5}, {0.1, 0, 0}, {0, 1, 0}, 20};
  scene.lights = {{LightKind::directional, {1, 0, 1}, {}, {1, 1, 1}, 1}};
  const Material& m = scene.material;
  const Rgb ambient_only = m.ambient * m.diffuse;
  const Image shadowed = render_cpu(scene, {21, 21});
  EXPECT_NEAR(shadowed.at(10, 10).r, ambient_only.r, 1e-7);
  scene.triangles.pop_back();
  const Image lit = render_cpu(scene, {21, 21});
  EXPECT_GT(lit.at(10, 10).r, ambient_only.r + 0.1);
}

TEST(Meshes, PointLightsAreShadowedOnlyByWhatLiesBeforeThem) {
  Scene scene = default_scene(make_model("phong", {{"n", 5}}));
  scene.spheres = {{{0, 0, 0}, 1}, {{0, 0, 3}, 0.5}};  // the small sphere sits beyond the light
  scene.lights = {{LightKind::point, {}, {0, 0, 1.5}, {1, 1, 1}, 1}};
  scene.camera = {{0, 0.001, 1.4}, {0, 0, 0}, {0, 1, 0}, 10};
  const Image image = render_cpu(scene, {9, 9});
  EXPECT_GT(image.at(4, 4).r, 0.1);
}

TEST(Render, WithoutLightsShowsTheAmbientTermOnly) {
  Scene scene = default_scene(make_model("phong"));
  scene.lights.clear();
  const Image image = render_cpu(scene, {9, 9});
  const Rgb ambient = scene.material.ambient * scene.material.diffuse;
  EXPECT_FLOAT_EQ(image.at(4, 4).r, ambient.r);
  EXPECT_EQ(image.at(0, 0), (Rgb{}));
}

TEST(Render, RejectsZeroSizesAndInvalidScenes) {
  const Scene scene = default_scene(make_model("phong"));
  for (const auto& [w, h] : {std::pair{0, 10}, {10, 0}, {0, 0}}) {
    try {
      render_cpu(scene, {w, h});
      ADD_FAILURE() << w << "x" << h;
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr("image size"));
    }
  }
  Scene bad = scene;
  bad.camera.vertical_fov_deg = 0;
  EXPECT_THROW(render_cpu(bad, {4, 4}), InvalidArgument);
}

}  // namespace
}  // namespace specula::render
