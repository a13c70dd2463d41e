// Environment lighting (include/specula/render/environment.h): the white furnace against the models'
// albedo, energy bounds with their negative control, a synthetic lat-long probe against an
// independent quadrature, shadows from the environment, determinism, bad input.
#include "specula/render/environment.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <optional>

#include "render_support.h"
#include "specula/analysis/albedo.h"
#include "specula/exceptions.h"
#include "specula/catalogue/model_file.h"
#include "specula/render/image_io.h"

namespace specula::render {
namespace {

using ::testing::HasSubstr;
using specula::testing::pixel_ray;
using specula::testing::TempDir;

constexpr double kPi = std::numbers::pi;
constexpr int kSide = 24;

/// Where the ray meets the unit sphere at the origin: the outward normal there.
std::optional<Vec3> unit_sphere_normal(const Ray& ray) {
  const double b = dot(ray.origin, ray.direction), c = dot(ray.origin, ray.origin) - 1;
  const double discriminant = b * b - c;
  if (discriminant < 0) return std::nullopt;
  return ray.origin + ray.direction * (-b - std::sqrt(discriminant));
}

Scene bare_scene(const Model& model) {
  Scene scene = default_scene(model);
  scene.lights.clear();
  scene.material.diffuse = {0, 0, 0};
  scene.material.specular = {1, 1, 1};
  scene.material.ambient = {0, 0, 0};
  return scene;
}

/// One pixel's Monte-Carlo estimate: the mean of independent renders and its standard error.
struct Estimate {
  double mean = 0, standard_error = 0;
};

/// The red channel of every pixel over renders with seeds 1…seeds (each its own estimate).
std::vector<Estimate> estimates(const Scene& scene, const Environment& env, int side, int samples, int seeds = 8,
                                EnvironmentEstimator estimator = EnvironmentEstimator::mis) {
  std::vector<std::vector<double>> values(std::size_t(side) * side);
  for (int seed = 1; seed <= seeds; ++seed) {
    const Image image = render_environment(scene, env, {side, side}, {samples, std::uint64_t(seed), estimator});
    for (std::size_t i = 0; i < values.size(); ++i) values[i].push_back(image.samples()[3 * i]);
  }
  std::vector<Estimate> result;
  for (const auto& v : values) {
    double mean = 0, square = 0;
    for (const double x : v) mean += x / seeds;
    for (const double x : v) square += (x - mean) * (x - mean);
    result.push_back({mean, std::sqrt(square / (seeds - 1) / seeds)});
  }
  return result;
}

/// How far the estimates of the sphere's pixels are from `expected(N, V)`, in standard errors.
struct Deviation {
  double max_abs_z = 0;     ///< the largest |estimate − expected| / standard error
  double mean_square_z = 0; ///< ≈ 1 for an unbiased estimate
  double max_excess_z = 0;  ///< the largest (estimate − 1) / standard error: light created
  int pixels = 0;
};

/// The floor under a standard error: the reference's own error and the image's float rounding.
constexpr double kAlbedoErrorFloor = 1e-6;

/// f(x, y, N, V) for each pixel whose ray meets the sphere.
template <class F>
void for_each_sphere_pixel(const Camera& camera, F&& f) {
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const Ray ray = pixel_ray(camera, x, y, kSide, kSide);
      if (const auto n = unit_sphere_normal(ray)) f(x, y, *n, -ray.direction);
    }
}

template <class Expected>
Deviation deviation(const std::vector<Estimate>& e, const Camera& camera, const Expected& expected,
                    double error_floor = kAlbedoErrorFloor) {
  Deviation d;
  for_each_sphere_pixel(camera, [&](int x, int y, const Vec3& n, const Vec3& v) {
    const Estimate& p = e[std::size_t(y) * kSide + x];
    const double se = p.standard_error + error_floor;
    const double z = (p.mean - expected(n, v)) / se;
    d.max_abs_z = std::max(d.max_abs_z, std::abs(z));
    d.mean_square_z += z * z;
    d.max_excess_z = std::max(d.max_excess_z, (p.mean - 1) / se);
    ++d.pixels;
  });
  d.mean_square_z /= d.pixels;
  return d;
}

/// ρ(θ_v) of `model` at the angle between n and v, from one albedo_curve over the distinct angles
/// of the sphere's pixels (the image's symmetries repeat each angle up to eight times).
class AlbedoOfPixels {
 public:
  AlbedoOfPixels(const Model& model, const Camera& camera) {
    for_each_sphere_pixel(camera, [&](int, int, const Vec3& n, const Vec3& v) {
      albedo_.emplace(key(n, v), std::acos(std::min(1.0, dot(n, v))));
    });
    std::vector<double> thetas;
    for (const auto& [k, theta] : albedo_) thetas.push_back(theta);
    const std::vector<double> values = analysis::albedo_curve(model, thetas);
    std::size_t i = 0;
    for (auto& [k, value] : albedo_) value = values[i++];
  }
  double operator()(const Vec3& n, const Vec3& v) const { return albedo_.at(key(n, v)); }

 private:
  static long long key(const Vec3& n, const Vec3& v) { return std::llround(dot(n, v) * 1e9); }
  std::map<long long, double> albedo_;  ///< θ_v, then ρ(θ_v), by cos θ_v
};

/// The white furnace image of `model` against the albedo ρ(θ_v) of `reference`.
Deviation furnace_against_albedo(const Model& model, const Model& reference, int samples = 32) {
  const Scene scene = bare_scene(model);
  const auto e = estimates(scene, Environment::uniform({1, 1, 1}), kSide, samples);
  return deviation(e, scene.camera, AlbedoOfPixels(reference, scene.camera));
}

std::vector<Model> furnace_models() {
  static const auto user = load_model_file(SPECULA_SOURCE_DIR "/examples/models/builtin-copies.toml");
  const auto my_ggx = std::find_if(user.begin(), user.end(), [](const ModelInfo& i) { return i.id == "my-ggx"; });
  return {make_model("ggx", {{"alpha", 0.3}}), make_model("ggx", {{"alpha", 0.08}}),
          make_model("log-normalized", {{"n", 20}}), make_model("phong-normalized", {{"n", 50}}),
          make_model(std::make_shared<const ModelInfo>(*my_ggx), {{"alpha", 0.3}})};
}

// Eight seeds give each pixel a Student's t with 7 degrees of freedom: E z² = 7/5, and
// P(|z| > 5.5) ≈ 1e-3, about one pixel in the five models' 1660.
TEST(WhiteFurnace, EachPixelIsTheModelsAlbedoAndNoneIsBrighterThanTheEnvironment) {
  for (const Model& model : furnace_models()) {
    const Deviation d = furnace_against_albedo(model, model);
    EXPECT_LT(d.max_abs_z, 6) << model.id();
    EXPECT_GT(d.mean_square_z, 0.9) << model.id();  // the standard errors are not too generous
    EXPECT_LT(d.mean_square_z, 2.2) << model.id();
    EXPECT_LT(d.max_excess_z, 4) << model.id();
  }
}

TEST(WhiteFurnace, TheAlbedoCheckFailsAgainstAnotherRoughness) {
  const Deviation d = furnace_against_albedo(make_model("ggx", {{"alpha", 0.3}}), make_model("ggx", {{"alpha", 0.6}}));
  EXPECT_GT(d.max_abs_z, 20);
}

/// The white furnace image of `model` against 1 at every pixel, within the Monte-Carlo error and
/// `stated_error` (a compensated model's albedo is 1 within its table's error).
Deviation furnace_against_one(const Model& model, double stated_error) {
  const Scene scene = bare_scene(model);
  // 16 seeds: Student's t with 15 degrees of freedom, P(|z| > 6) ≈ 2e-5 per pixel.
  const auto e = estimates(scene, Environment::uniform({1, 1, 1}), kSide, 32, 16);
  return deviation(e, scene.camera, [](const Vec3&, const Vec3&) { return 1.0; }, stated_error);
}

double albedo_error(const Model& compensated) { return compensated.compensated()->table->albedo_error; }

// Kulla-Conty's compensation makes GGX with F = 1 reflect all it receives at every angle: the
// furnace image is flat. Without it, rough GGX loses energy at grazing angles (negative control).
TEST(WhiteFurnace, GgxWithMultipleScatteringIsFlat) {
  for (double alpha : {0.3, 0.8}) {
    const Model model = make_model("ggx+ms", {{"alpha", alpha}});
    const Deviation d = furnace_against_one(model, albedo_error(model));
    EXPECT_LT(d.max_abs_z, 6) << "alpha " << alpha;
    EXPECT_LT(d.max_excess_z, 4) << "alpha " << alpha;
  }
  const Model rough = make_model("ggx+ms", {{"alpha", 0.8}});
  EXPECT_GT(furnace_against_one(make_model("ggx", {{"alpha", 0.8}}), albedo_error(rough)).max_abs_z, 20);
}

TEST(WhiteFurnace, CookTorrance1982IsCaughtCreatingLight) {
  const Model model = make_model("cook-torrance-1982");
  EXPECT_GT(furnace_against_albedo(model, model).max_excess_z, 50);
}

// ---- latitude-longitude probes ---------------------------------------------------------------

/// The direction the centre of map pixel (x, y) of a w × h map looks toward (docs/render.md):
/// row 0 up +y, the centre column toward −z, columns to its right toward +x.
Vec3 map_direction(double x, double y, int w, int h) {
  const double theta = kPi * y / h, phi = 2 * kPi * x / w - kPi;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

Image constant_map(int w, int h, const Rgb& value) {
  Image map(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) map.set(x, y, value);
  return map;
}

Environment through_exr(const TempDir& dir, const Image& map) {
  write_exr(dir / "probe.exr", map, ExrPixel::float32);
  return read_environment(dir / "probe.exr");
}

TEST(LatLongProbe, AConstantMapIsTheWhiteFurnace) {
  TempDir dir;
  const Model model = make_model("ggx", {{"alpha", 0.3}});
  const Scene scene = bare_scene(model);
  const auto e = estimates(scene, through_exr(dir, constant_map(8, 4, {1, 1, 1})), kSide, 32);
  const Deviation d = deviation(e, scene.camera, AlbedoOfPixels(model, scene.camera));
  EXPECT_LT(d.max_abs_z, 6);
  EXPECT_LT(d.mean_square_z, 2.2);
}

TEST(LatLongProbe, RaysThatMissSeeTheMapPixelOfTheirDirection) {
  TempDir dir;
  const int w = 16, h = 8;
  Image map(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) map.set(x, y, {double(y * w + x + 1), 0, 0});
  const Scene scene = bare_scene(make_model("ggx"));
  const Image image = render_environment(scene, through_exr(dir, map), {kSide, kSide}, {1, 0});
  int background = 0;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const Ray ray = pixel_ray(scene.camera, x, y, kSide, kSide);
      if (unit_sphere_normal(ray)) continue;
      const Vec3 d = ray.direction;
      const double theta = std::acos(d.y), phi = std::atan2(d.x, -d.z);
      const int mx = int((phi + kPi) / (2 * kPi) * w), my = int(theta / kPi * h);
      EXPECT_EQ(image.at(x, y).r, my * w + mx + 1) << x << "," << y;
      ++background;
    }
  EXPECT_GT(background, 200);
  // The orientation itself: the map's centre column looks toward −z, row 0 toward +y.
  EXPECT_NEAR(map_direction(w / 2.0, h / 2.0, w, h).z, -1, 1e-15);
  EXPECT_NEAR(map_direction(0, 0, w, h).y, 1, 1e-15);
}

/// A bright patch of map pixels [12, 14) × [2, 4) of a 16 × 8 map (up and to the front right of
/// the sphere), black elsewhere.
Image patch_map() {
  Image map = constant_map(16, 8, {0, 0, 0});
  for (int y = 2; y < 4; ++y)
    for (int x = 12; x < 14; ++x) map.set(x, y, {40, 20, 10});
  return map;
}

/// L_o of the red channel by the midpoint rule on a 24 × 24 grid in (θ, φ) over each patch pixel
/// (the patch's columns from first_column),
/// dω = sin θ dθ dφ: no sampling, no distribution.
double patch_quadrature(const Material& m, const Vec3& n, const Vec3& v, int first_column = 12) {
  const int grid = 24;
  const double step_x = 2 * kPi / 16 / grid, step_y = kPi / 8 / grid;
  double sum = 0;
  for (int i = 0; i < 2 * grid; ++i)
    for (int j = 0; j < 2 * grid; ++j) {
      const double x = first_column + (i + 0.5) / grid, y = 2 + (j + 0.5) / grid;
      const Vec3 l = map_direction(x, y, 16, 8);
      const double cos_l = dot(n, l);
      if (cos_l <= 0) continue;
      const double f = m.specular.r * m.model(n, l, v) + m.diffuse.r / kPi;
      sum += 40 * f * cos_l * std::sin(kPi * y / 8) * step_x * step_y;
    }
  return sum;
}

TEST(LatLongProbe, ABrightPatchMatchesAnIndependentQuadrature) {
  TempDir dir;
  Scene scene = bare_scene(make_model("ggx", {{"alpha", 0.4}}));
  scene.material.diffuse = {0.3, 0.3, 0.3};
  scene.material.specular = {0.7, 0.7, 0.7};
  const auto e = estimates(scene, through_exr(dir, patch_map()), kSide, 64, 16);
  const auto expected = [&](const Vec3& n, const Vec3& v) { return patch_quadrature(scene.material, n, v); };
  // The midpoint rule's error where the horizon cuts the patch: ~1e-5 (24 against 72 points a side).
  const double quadrature_error = 1e-4;
  const Deviation d = deviation(e, scene.camera, expected, quadrature_error);
  EXPECT_LT(d.max_abs_z, 6);
  EXPECT_LT(d.mean_square_z, 2.2);
  // Negative control: the same patch one pixel to the left is another image.
  const auto moved = [&](const Vec3& n, const Vec3& v) {
    return patch_quadrature(scene.material, n, v, 11);
  };
  EXPECT_GT(deviation(e, scene.camera, moved, quadrature_error).max_abs_z, 20);
}

/// The mean standard error over the sphere's pixels: the estimator's noise.
double mean_standard_error(const std::vector<Estimate>& e, const Camera& camera) {
  double sum = 0;
  int pixels = 0;
  for_each_sphere_pixel(camera, [&](int x, int y, const Vec3&, const Vec3&) {
    sum += e[std::size_t(y) * kSide + x].standard_error;
    ++pixels;
  });
  return sum / pixels;
}

// BRDF Explorer's estimators (uniform, light, BRDF, MIS) each converge to the same image; they
// differ in noise. Under a constant map every one of them matches the albedo.
TEST(LatLongProbe, EveryEstimatorMatchesTheAlbedoUnderAConstantMap) {
  TempDir dir;
  const Model model = make_model("ggx", {{"alpha", 0.3}});
  const Scene scene = bare_scene(model);
  const Environment env = through_exr(dir, constant_map(8, 4, {1, 1, 1}));
  for (std::size_t k = 0; k < kEnvironmentEstimatorCount; ++k) {
    const auto estimator = static_cast<EnvironmentEstimator>(k);
    const Deviation d = deviation(estimates(scene, env, kSide, 32, 8, estimator), scene.camera, AlbedoOfPixels(model, scene.camera));
    EXPECT_LT(d.max_abs_z, 6) << to_string(estimator);
    EXPECT_LT(d.mean_square_z, 2.2) << to_string(estimator);
  }
}

// A small bright patch, diffuse and specular: the estimators that sample the light find it and
// match the quadrature, uniform sampling with more noise than MIS. (BRDF sampling alone misses the
// patch at most pixels for these sample counts: its estimate is unbiased but far from normal, so no
// z-test applies to it; the constant map above checks it.)
TEST(LatLongProbe, TheLightSamplingEstimatorsMatchTheQuadratureOfABrightPatch) {
  TempDir dir;
  Scene scene = bare_scene(make_model("ggx", {{"alpha", 0.4}}));
  scene.material.diffuse = {0.3, 0.3, 0.3};
  scene.material.specular = {0.7, 0.7, 0.7};
  const Environment env = through_exr(dir, patch_map());
  const auto expected = [&](const Vec3& n, const Vec3& v) { return patch_quadrature(scene.material, n, v); };
  std::map<EnvironmentEstimator, double> noise;
  for (const auto estimator : {EnvironmentEstimator::uniform, EnvironmentEstimator::environment, EnvironmentEstimator::mis}) {
    const auto e = estimates(scene, env, kSide, 64, 16, estimator);
    const Deviation d = deviation(e, scene.camera, expected, 1e-4);
    EXPECT_LT(d.max_abs_z, 6.5) << to_string(estimator);
    EXPECT_LT(d.mean_square_z, 2.2) << to_string(estimator);
    noise[estimator] = mean_standard_error(e, scene.camera);
  }
  EXPECT_GT(noise[EnvironmentEstimator::uniform], 1.5 * noise[EnvironmentEstimator::mis]);
  EXPECT_GT(noise[EnvironmentEstimator::uniform], 1.5 * noise[EnvironmentEstimator::environment]);
}

// ---- shadows ------------------------------------------------------------------------------------

/// A Lambertian floor z = 0 (ρ_d = 1) under the white furnace, with a sphere over it. A point p of
/// the floor sees a sphere of radius r at distance d, its centre at angle β from the normal, as a
/// cap of half-angle α = asin(r/d); the cap's projected solid angle is π sin²α cos β (while
/// α + β < 90°), so L_o(p) = 1 − sin²α cos β.
TEST(Shadows, AnOccluderDimsTheFloorByItsProjectedSolidAngle) {
  Scene scene = bare_scene(make_model("ggx"));
  scene.material.diffuse = {1, 1, 1};
  scene.material.specular = {0, 0, 0};
  const Vec3 a{-3, -3, 0}, b{3, -3, 0}, c{3, 3, 0}, d{-3, 3, 0};
  scene.triangles = {Triangle{{a, b, c}, {}, false}, Triangle{{a, c, d}, {}, false}};
  const Sphere occluder{{0.5, 0, 0.8}, 0.5};
  scene.spheres = {occluder};
  // Pixel (1, 2) of 5 × 5 looks at p on the floor, clear of the sphere.
  const Ray ray = pixel_ray(scene.camera, 1, 2, 5, 5);
  const Vec3 p = ray.origin + ray.direction * (-ray.origin.z / ray.direction.z);
  const Vec3 to_centre = occluder.centre - p;
  const double distance = std::sqrt(dot(to_centre, to_centre));
  const double sin_alpha = occluder.radius / distance, cos_beta = to_centre.z / distance;
  ASSERT_LT(std::asin(sin_alpha) + std::acos(cos_beta), kPi / 2);
  const double expected = 1 - sin_alpha * sin_alpha * cos_beta;

  const Estimate shaded = estimates(scene, Environment::uniform({1, 1, 1}), 5, 1024)[2 * 5 + 1];
  EXPECT_NEAR(shaded.mean, expected, 5 * shaded.standard_error);
  scene.spheres.clear();  // negative control: without the occluder the floor shows 1
  const Estimate open = estimates(scene, Environment::uniform({1, 1, 1}), 5, 1024)[2 * 5 + 1];
  EXPECT_NEAR(open.mean, 1, 5 * open.standard_error);
  EXPECT_GT(open.mean - shaded.mean, 10 * shaded.standard_error);
}

// ---- determinism and bad input --------------------------------------------------------------------

TEST(Determinism, ImagesAreBitIdenticalForAnyThreadCountAndDependOnTheSeed) {
  TempDir dir;
  Scene scene = default_scene(make_model("log-normalized", {{"n", 50}}));
  scene.lights.clear();
  scene.spheres.push_back({{1.2, 0.3, -0.5}, 0.6});
  const Environment env = through_exr(dir, patch_map());
  const auto render = [&](int threads, std::uint64_t seed) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    return render_environment(scene, env, {37, 29}, {8, seed});
  };
  const Image first = render(1, 5);
  const auto bytes = first.samples().size_bytes();
  for (const int threads : {2, 3, 8})
    EXPECT_EQ(std::memcmp(render(threads, 5).samples().data(), first.samples().data(), bytes), 0) << threads;
  EXPECT_NE(std::memcmp(render(2, 6).samples().data(), first.samples().data(), bytes), 0);
}

std::string error_of(const auto& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

// The sample counts' check names the field by key, spelled as the interface that asks spells it:
// the CLI checks --samples with it before it renders.
TEST(EnvironmentErrors, TheSampleCheckSpellsItsFieldAsAsked) {
  const auto message = [](Spelling spelling, RenderSettings size, int samples) {
    try {
      check_samples(size, {samples, 0}, spelling);
    } catch (const InvalidField& e) {
      return e.field() + ": " + e.what();
    }
    return std::string("no error");
  };
  EXPECT_EQ(message(Spelling::option, {4, 4}, 1), "no error");  // control
  EXPECT_EQ(message(Spelling::option, {4, 4}, 0), "samples: --samples 0 is outside [1, 65536]");
  EXPECT_EQ(message(Spelling::key, {4, 4}, 0), "samples: samples 0 is outside [1, 65536]");
  EXPECT_THAT(message(Spelling::option, {1024, 1024}, 65), HasSubstr("pixels with --samples 65 is"));
}

TEST(EnvironmentErrors, LightsSampleCountsAndBadMapPixelsAreRefused) {
  const Scene bare = bare_scene(make_model("ggx"));
  const Environment white = Environment::uniform({1, 1, 1});
  const auto render = [&](const Scene& s, RenderSettings size, int samples) {
    return error_of([&] { render_environment(s, white, size, {samples, 0}); });
  };
  EXPECT_EQ(render(bare, {4, 4}, 1), "no error");  // control
  EXPECT_THAT(render(default_scene(make_model("ggx")), {4, 4}, 1), HasSubstr("no other lights"));
  EXPECT_EQ(render(bare, {4, 4}, 0), "samples 0 is outside [1, 65536]");  // by its key, as a library names it
  EXPECT_THAT(render(bare, {4, 4}, 65537), HasSubstr("outside"));
  EXPECT_THAT(render(bare, {1024, 1024}, 65), HasSubstr("more than the 2^26"));
  EXPECT_THAT(render(bare, {256, 256}, 1025), HasSubstr("more than the 2^26"));
  Image map = constant_map(4, 2, {1, 1, 1});
  EXPECT_EQ(error_of([&] { Environment::lat_long(map); }), "no error");  // control
  map.set(3, 1, {1, -1, 1});
  EXPECT_EQ(error_of([&] { Environment::lat_long(map); }), "environment map pixel (3, 1) is negative or not finite");
  map.set(3, 1, {1, std::nan(""), 1});
  EXPECT_THAT(error_of([&] { Environment::lat_long(map); }), HasSubstr("(3, 1)"));
  EXPECT_THAT(error_of([] { read_environment("/nonexistent/probe.exr"); }), HasSubstr("cannot read"));
}

}  // namespace
}  // namespace specula::render
