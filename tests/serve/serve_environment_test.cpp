// The lit-object view's server side (docs/serve.md): uploads of OBJ meshes and probes, parsed once
// and refused in one line when malformed, huge or not finite; render jobs that refine their image
// pass after pass, each frame the CPU renderer's mean of the same passes, byte for byte.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <functional>
#include <limits>
#include <thread>
#include <unistd.h>

#include "serve_support.h"
#include "specula/catalogue/model_file.h"
#include "specula/io/base64.h"
#include "specula/io/files.h"
#include "specula/render/environment.h"
#include "specula/render/image_io.h"
#include "specula/sampling/seeds.h"

namespace specula::serve {
namespace {

using json = nlohmann::json;
using specula::testing::Answer;
using specula::testing::get;
using specula::testing::post;
using specula::testing::post_json;
using specula::testing::TestServer;
using ::testing::HasSubstr;

constexpr const char* kTetrahedron =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

render::Image grey(int width, int height) {
  render::Image image(width, height);
  for (float& sample : image.samples()) sample = 0.5f;
  return image;
}

/// The image as an EXR file's bytes (float samples), through a file of this process's own.
std::string exr_bytes(const render::Image& image) {
  const auto path = std::filesystem::temp_directory_path() / fmt::format("specula-serve-probe-{}.exr", ::getpid());
  render::write_exr(path, image, render::ExrPixel::float32);
  std::string bytes = io::read_file(path);
  std::filesystem::remove(path);
  return bytes;
}

json poll_render(int port, std::int64_t id, const std::function<bool(const json&)>& done) {
  return specula::testing::poll_job(port, fmt::format("/api/environment/{}", id), done, 50);
}

std::int64_t start_render(int port, const json& request) {
  const Answer a = post_json(port, "/api/environment", request);
  EXPECT_EQ(a.status, 202) << a.body;
  return a.status == 202 ? a.json()["job"].get<std::int64_t>() : -1;
}

/// What the job's frame after `target` samples must be: the passes of 1, 2, 4, 8, 16, 16, …
/// samples (the last what is left), pass k seeded stream_key(seed, k), averaged by their samples.
std::string expected_frame(const render::Scene& scene, const render::Environment& env, render::RenderSettings size,
                           int target, std::uint64_t seed, render::EnvironmentEstimator estimator) {
  std::vector<double> sum(std::size_t(3) * size.width * size.height, 0.0);
  int done = 0;
  for (int pass = 0; done < target; ++pass) {
    const int n = std::min({1 << std::min(pass, 4), target - done});
    const auto image = render::render_environment(scene, env, size, {n, sampling::stream_key(seed, std::uint64_t(pass)), estimator});
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += double(image.samples()[i]) * n;
    done += n;
  }
  render::Image mean(size.width, size.height);
  for (std::size_t i = 0; i < sum.size(); ++i) mean.samples()[i] = static_cast<float>(sum[i] / done);
  render::Display display;
  display.tone_map = render::ToneMap::aces;
  return io::base64(render::png_bytes(mean, display));
}

render::Scene specular_only(const Model& model) {
  render::Scene scene = render::default_scene(model);
  scene.lights.clear();
  scene.material.diffuse = {0, 0, 0};
  scene.material.specular = {1, 1, 1};
  scene.material.ambient = {0, 0, 0};
  return scene;
}

TEST(ServeEnvironment, AJobsFramesAreTheRenderersMeanOfItsPasses) {
  TestServer server;
  const json request{{"model", "ggx"}, {"params", {{"alpha", 0.3}}}, {"obj", "sphere"}, {"probe", "furnace"},
                     {"size", {16, 12}}, {"samples", 40}, {"seed", 7}, {"estimator", "brdf"}};
  const std::int64_t id = start_render(server.port(), request);
  const json status = poll_render(server.port(), id, [](const json& s) { return s["state"] == "done"; });
  ASSERT_EQ(status["state"], "done") << status.dump(2);
  EXPECT_EQ(status["samples"], 40);
  EXPECT_EQ(status["target"], 40);
  EXPECT_EQ(status["estimator"], "brdf");
  const render::Scene scene = specular_only(make_model("ggx", {{"alpha", 0.3}}));
  const auto furnace = render::Environment::uniform({1, 1, 1});
  const auto brdf = render::EnvironmentEstimator::brdf;
  EXPECT_EQ(status["png"], expected_frame(scene, furnace, {16, 12}, 40, 7, brdf));
  // Negative controls: another seed, another estimator, one pass fewer are other images.
  EXPECT_NE(status["png"], expected_frame(scene, furnace, {16, 12}, 40, 8, brdf));
  EXPECT_NE(status["png"], expected_frame(scene, furnace, {16, 12}, 40, 7, render::EnvironmentEstimator::mis));
  EXPECT_NE(status["png"], expected_frame(scene, furnace, {16, 12}, 24, 7, brdf));
}

TEST(ServeEnvironment, TheBundledKnotUnderTheBundledSkyShowsAFirstFrameAtOnce) {
  TestServer server;
  for (const char* estimator : {"uniform", "environment", "brdf", "mis"}) {
    const std::int64_t id = start_render(server.port(), {{"model", "phong-normalized"}, {"params", {{"n", 50}}},
                                                  {"size", {24, 24}}, {"estimator", estimator}});
    const json status = poll_render(server.port(), id, [](const json& s) { return s["samples"].get<int>() > 0; });
    EXPECT_GT(status["samples"].get<int>(), 0) << status.dump(2);
    EXPECT_EQ(status["obj"], "bundled");
    EXPECT_EQ(status["probe"], "bundled");
    EXPECT_FALSE(status["png"].get<std::string>().empty());
    EXPECT_EQ(specula::testing::del(server.port(), fmt::format("/api/environment/{}", id)).status, 200);
  }
}

TEST(ServeEnvironment, AnUploadedMeshAndProbeRender) {
  TestServer server;
  const Answer obj = post(server.port(), "/api/upload/obj", kTetrahedron);
  ASSERT_EQ(obj.status, 201) << obj.body;
  EXPECT_EQ(obj.json()["triangles"], 4);
  const std::string png = render::png_bytes(grey(4, 2), render::Display{});
  const Answer probe = post(server.port(), "/api/upload/probe", png);
  ASSERT_EQ(probe.status, 201) << probe.body;
  EXPECT_EQ(probe.json()["width"], 4);
  const std::int64_t id = start_render(server.port(), {{"model", "ggx"}, {"obj", obj.json()["obj"]}, {"probe", probe.json()["probe"]},
                                                {"size", {8, 8}}, {"samples", 2}});
  EXPECT_EQ(poll_render(server.port(), id, [](const json& s) { return s["state"] == "done"; })["state"], "done");
}

/// A 400 or 413 whose one-line error contains `what`.
void expect_refused(const Answer& a, int status, const std::string& what) {
  EXPECT_EQ(a.status, status) << a.body;
  const json error = json::parse(a.body, nullptr, false);
  ASSERT_TRUE(error.is_object()) << a.body;
  EXPECT_THAT(error["error"].get<std::string>(), HasSubstr(what));
  EXPECT_EQ(error["error"].get<std::string>().find('\n'), std::string::npos);
}

TEST(ServeEnvironment, BadUploadsAreRefusedInOneLine) {
  serve::Limits limits;
  limits.max_upload_bytes = 4096;
  limits.max_upload_triangles = 3;
  limits.max_probe_pixels = 100;
  limits.max_kept_uploads = 2;
  TestServer server(limits);
  const int port = server.port();
  expect_refused(post(port, "/api/upload/obj", "v 0 0 0\nf 1 2 3\n"), 400, "beyond");
  expect_refused(post(port, "/api/upload/obj", "v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), 400, "not finite");
  expect_refused(post(port, "/api/upload/obj", "hello\n"), 400, "no triangles");
  expect_refused(post(port, "/api/upload/obj", kTetrahedron), 400, "4 triangles; at most 3");
  expect_refused(post(port, "/api/upload/obj", std::string(5000, 'v')), 413, "at most 4096");
  expect_refused(post(port, "/api/upload/probe", "GIF89a"), 400, "neither a PNG nor an OpenEXR");
  render::Image nan = grey(4, 2);
  nan.set(3, 1, {std::numeric_limits<float>::quiet_NaN(), 0, 0});
  expect_refused(post(port, "/api/upload/probe", exr_bytes(nan)), 400, "pixel (3, 1)");
  expect_refused(post(port, "/api/upload/probe", exr_bytes(render::Image(20, 10))), 400, "more than the 100 pixels");
  // A truncated EXR: OpenEXR's own error, in one line.
  const std::string whole = exr_bytes(nan);
  expect_refused(post(port, "/api/upload/probe", whole.substr(0, whole.size() / 2)), 400, "cannot read 'the probe'");
  // Only the newest uploads are kept; a job naming a dropped or unknown one is refused.
  const Answer first = post(port, "/api/upload/obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ASSERT_EQ(first.status, 201);
  for (int i = 0; i < 2; ++i) ASSERT_EQ(post(port, "/api/upload/obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").status, 201);
  expect_refused(post_json(port, "/api/environment", {{"model", "ggx"}, {"obj", first.json()["obj"]}}), 400, "kept upload");
  expect_refused(post_json(port, "/api/environment", {{"model", "ggx"}, {"probe", "../etc/passwd"}}), 400, "kept upload");
  expect_refused(post_json(port, "/api/environment", {{"model", "ggx"}, {"size", {4096, 4096}}}), 400, "size");
  expect_refused(post_json(port, "/api/environment", {{"model", "ggx"}, {"samples", 100000}}), 400, "samples");
  expect_refused(post_json(port, "/api/environment", {{"model", "ggx"}, {"estimator", "magic"}}), 400, "uniform, environment, brdf, mis");
}

}  // namespace
}  // namespace specula::serve
