// The page in a real browser: Debian's chromium, headless with SwiftShader's WebGL2, driven by
// chromedriver. It loads from the server's embedded assets, renders each model's sphere with the
// shader the server emits — pixels within a tolerance of the CPU renderer's image of the same
// scene — re-renders when a slider moves (by keyboard) or a model is picked, keeps its state in
// the URL, draws its plots, runs a fit, adds a model typed into its editor (or shows the server's
// error next to the formula), and fits a phone-width screen.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <numbers>

#include "serve_support.h"
#include "specula/brdf/directions.h"
#include "specula/catalogue/model_file.h"
#include "specula/render/image.h"
#include "specula/render/render.h"
#include "specula/render/scene.h"
#include "webdriver.h"

namespace specula::serve {
namespace {

using json = nlohmann::json;
using specula::testing::TestServer;
using specula::testing::WebDriver;
using ::testing::HasSubstr;

constexpr int kSize = 96;
constexpr const char* kArrowLeft = "\ue012";

/// The CPU renderer's 8-bit sRGB image (RGB, top row first) of the page's scene for `model` with
/// the light at polar angle theta and azimuth phi (degrees) about the camera's axis.
std::vector<std::uint8_t> cpu_image(const Model& model, double theta, double phi) {
  render::Scene scene = render::default_scene(model);
  scene.lights[0].direction = from_spherical(radians(theta), radians(phi));
  return render::to_srgb8(render::render_cpu(scene, {kSize, kSize}), render::Display{});
}

std::string percent_encoded(const std::string& text) {
  std::string out;
  for (const unsigned char ch : text)
    out += std::isalnum(ch) || ch == '-' || ch == '_' || ch == '.' ? std::string(1, static_cast<char>(ch)) : fmt::format("%{:02X}", ch);
  return out;
}

struct Agreement {
  double within_2 = 0;  ///< fraction of pixels whose channels all differ by ≤ 2/255
  int max_difference = 0;
};

/// Compares the canvas's RGBA bytes with the CPU's RGB bytes.
Agreement compare(const json& rgba, const std::vector<std::uint8_t>& rgb) {
  Agreement a;
  const std::size_t pixels = rgb.size() / 3;
  if (rgba.size() != 4 * pixels) return a;
  std::size_t close = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(rgba[4 * p + c].get<int>() - int{rgb[3 * p + c]}));
    close += worst <= 2 ? 1 : 0;
    a.max_difference = std::max(a.max_difference, worst);
  }
  a.within_2 = static_cast<double>(close) / static_cast<double>(pixels);
  return a;
}

class Page : public ::testing::Test {
 protected:
  void SetUp() override {
    browser_ = std::make_unique<WebDriver>(SPECULA_CHROMEDRIVER, SPECULA_CHROMIUM, 1280, 800);
  }

  std::string base() const { return fmt::format("http://127.0.0.1:{}/", server_.port()); }

  void open(const json& state) {
    browser_->go(base() + "#state=" + percent_encoded(state.dump()));
    ASSERT_TRUE(wait_until_rendered(1));
  }

  /// Waits until the page has finished `count` renders and says "ready".
  bool wait_until_rendered(int count) {
    return browser_->wait_for(fmt::format(
        "return Number(document.body.dataset.renders || 0) >= {} && document.getElementById('status').textContent === 'ready';", count));
  }

  int renders() { return std::stoi(browser_->run("return document.body.dataset.renders || '0';").get<std::string>()); }

  json state() { return json::parse(browser_->run("return new URLSearchParams(location.hash.slice(1)).get('state');").get<std::string>()); }

  json sphere_pixels(int index) {
    return browser_->run(
        "const c = document.getElementById(arguments[0]); const copy = document.createElement('canvas');"
        "copy.width = c.width; copy.height = c.height; const x = copy.getContext('2d'); x.drawImage(c, 0, 0);"
        "return Array.from(x.getImageData(0, 0, c.width, c.height).data);",
        json::array({fmt::format("sphere-{}", index)}));
  }

  void expect_matches_cpu(int index, const Model& model, double theta, double phi) {
    const Agreement a = compare(sphere_pixels(index), cpu_image(model, theta, phi));
    EXPECT_GE(a.within_2, 0.999) << model.id() << ": max difference " << a.max_difference;
    EXPECT_LE(a.max_difference, 3) << model.id();  // SwiftShader here: at most 1/255
  }

  TestServer server_;
  std::unique_ptr<WebDriver> browser_;
};

const json kState = {{"models", {{{"id", "log-normalized"}, {"params", {{"n", 50}}}}, {{"id", "schlick"}, {"params", {{"n", 20}}}}}},
                     {"theta", 30}, {"phi", 135}, {"reference", "phong-normalized"}, {"size", kSize}};

TEST_F(Page, RendersEachModelLikeTheCpuRenderer) {
  open(kState);
  expect_matches_cpu(0, make_model("log-normalized", {{"n", 50}}), 30, 135);
  expect_matches_cpu(1, make_model("schlick", {{"n", 20}}), 30, 135);
  // Not a tautology: a different model is far from this image.
  EXPECT_LT(compare(sphere_pixels(0), cpu_image(make_model("schlick", {{"n", 20}}), 30, 135)).within_2, 0.99);
}

TEST_F(Page, ASliderMovedByKeyboardRerendersAndUpdatesTheUrl) {
  open(kState);
  const json before = sphere_pixels(0);
  const int done = renders();
  std::string keys;
  for (int i = 0; i < 40; ++i) keys += kArrowLeft;
  browser_->send_keys("#param-0-n", keys);
  ASSERT_TRUE(wait_until_rendered(done + 1));
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('status').textContent === 'ready';"));
  const double n = state()["models"][0]["params"]["n"].get<double>();
  EXPECT_LT(n, 50);
  const json after = sphere_pixels(0);
  EXPECT_NE(after, before);
  expect_matches_cpu(0, make_model("log-normalized", {{"n", n}}), 30, 135);
}

TEST_F(Page, PickingAModelShowsItsSphereAndPlots) {
  open(kState);
  const int done = renders();
  browser_->run("const s = document.getElementById('model-1'); s.value = 'ggx'; s.dispatchEvent(new Event('change'));");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  EXPECT_EQ(state()["models"][1]["id"], "ggx");
  expect_matches_cpu(1, make_model("ggx"), 30, 135);
  for (const char* plot : {"plot-lobe", "plot-polar", "plot-albedo"})
    EXPECT_EQ(browser_->run(fmt::format("return document.querySelectorAll('#{} polyline').length;", plot)), 2) << plot;
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-error polyline').length;"), 1);  // ggx is no lobe
  // The polar plot draws the incident and mirror directions; the energy plot E(μ) and, dashed, M+ms.
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-polar line.incident, #plot-polar line.mirror').length;"), 2);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-energy polyline').length;"), 4);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-energy polyline.band').length;"), 2);
  EXPECT_EQ(browser_->run("return document.querySelector('#coefficients tbody td:nth-child(3)').textContent;"), "10.108516");
  EXPECT_THAT(browser_->run("return document.getElementById('difference-caption').textContent;").get<std::string>(),
              HasSubstr("against phong-normalized"));
}

/// The θ_h × θ_d image of the page's slice section as the library computes it: 64 × 64 pixels,
/// column i at θ_h = (i + ½)·90/64°, row j at θ_d, grey = round(255·min(1, (max(0, f)·2^exposure)^(1/gamma)))
/// (docs/serve.md, web/slices.js).
std::vector<int> slice_image(const Model& model, double phi_d, double exposure, double gamma) {
  constexpr int n = 64;
  std::vector<int> grey(n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto [l, v] = from_half_difference(radians((i + 0.5) * 90 / n), radians((j + 0.5) * 90 / n), radians(phi_d));
      const double x = std::max(0.0, model({0, 0, 1}, l, v)) * std::exp2(exposure);
      grey[static_cast<std::size_t>(j * n + i)] = static_cast<int>(std::lround(255 * std::min(1.0, std::pow(x, 1 / gamma))));
    }
  return grey;
}

/// The largest difference between a slice canvas's grey and `expected`, and whether it is grey.
int slice_difference(WebDriver& browser, int index, const std::vector<int>& expected) {
  const json rgba = browser.run(
      "const c = document.getElementById(arguments[0]);"
      "return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);",
      json::array({fmt::format("slice-{}", index)}));
  if (rgba.size() != 4 * expected.size()) return 256;
  int worst = 0;
  for (std::size_t p = 0; p < expected.size(); ++p)
    for (std::size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(rgba[4 * p + c].get<int>() - expected[p]));
  return worst;
}

// The half/difference views: the θ_h and θ_d slices for every model, and each model's θ_h × θ_d
// image within 1/255 of the library's; exposure redraws it at once, without the server.
TEST_F(Page, TheHalfDifferenceSlicesMatchTheLibrary) {
  json page = kState;
  page["models"][1] = {{"id", "ggx"}, {"params", {{"alpha", 0.4}}}};
  page["slice"] = {{"theta_h", 20}, {"theta_d", 40}, {"phi_d", 60}, {"exposure", -1}, {"gamma", 2}};
  open(page);
  for (const char* plot : {"plot-theta-h", "plot-theta-d"})
    EXPECT_EQ(browser_->run(fmt::format("return document.querySelectorAll('#{} polyline').length;", plot)), 2) << plot;
  const Model log = make_model("log-normalized", {{"n", 50}}), ggx = make_model("ggx", {{"alpha", 0.4}});
  EXPECT_LE(slice_difference(*browser_, 0, slice_image(log, 60, -1, 2)), 1);
  EXPECT_LE(slice_difference(*browser_, 1, slice_image(ggx, 60, -1, 2)), 1);
  EXPECT_GT(slice_difference(*browser_, 1, slice_image(log, 60, -1, 2)), 16);  // control: another model's image
  const int done = renders();
  browser_->run("const e = document.getElementById('slice-exposure'); e.value = '2'; e.dispatchEvent(new Event('input'));");
  EXPECT_LE(slice_difference(*browser_, 1, slice_image(ggx, 60, 2, 2)), 1);
  EXPECT_EQ(renders(), done);  // no new request: the values it had, shown brighter
  EXPECT_EQ(state()["slice"]["exposure"], 2);
}

// The albedo view: beside each model's cubature curve, the chosen estimator's ±2σ band, dashed.
TEST_F(Page, TheAlbedoPlotShowsTheEstimatorsBand) {
  json page = kState;
  page["estimator"] = "sampler";
  page["samples"] = 1000;
  open(page);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-albedo polyline').length;"), 6);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-albedo polyline.band').length;"), 4);
  const int done = renders();
  browser_->run("const s = document.getElementById('albedo-estimator'); s.value = ''; s.dispatchEvent(new Event('change'));");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-albedo polyline.band').length;"), 0);
  EXPECT_EQ(state()["estimator"], "");
}

/// The lobe plot's largest y tick (the plot's upper end, as printed).
double lobe_plot_top(WebDriver& browser) {
  return std::stod(browser.run("const t = [...document.querySelectorAll('#plot-lobe text')].map((e) => e.textContent);"
                               "return t[3];").get<std::string>());
}

// BRDF Explorer's switches: log10(x + 1) and × N·L change every plot of f; a model unticked (or
// another one soloed) leaves the plots.
TEST_F(Page, ThePlotSwitchesAndVisibilityReachEveryPlot) {
  json page = kState;
  page["models"][1] = {{"id", "ggx"}, {"params", {{"alpha", 0.3}}}};
  open(page);
  const double top = lobe_plot_top(*browser_);
  int done = renders();
  browser_->run("const c = document.getElementById('plot-log'); c.checked = true; c.dispatchEvent(new Event('change'));");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  EXPECT_NEAR(lobe_plot_top(*browser_), std::log10(top + 1), 0.01 * std::log10(top + 1));
  EXPECT_THAT(browser_->run("return document.querySelector('#plot-theta-h svg').textContent;").get<std::string>(), HasSubstr("0"));
  done = renders();
  browser_->run("const c = document.getElementById('plot-times-cos'); c.checked = true; c.dispatchEvent(new Event('change'));");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  EXPECT_EQ(state()["timesCos"], true);
  EXPECT_THAT(browser_->run("return document.querySelector('#plot-lobe svg').textContent;").get<std::string>(), HasSubstr("· N·L"));
  done = renders();
  browser_->run("const c = document.getElementById('visible-1'); c.checked = false; c.dispatchEvent(new Event('change'));");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  for (const char* plot : {"plot-lobe", "plot-polar", "plot-theta-h"})
    EXPECT_EQ(browser_->run(fmt::format("return document.querySelectorAll('#{} polyline').length;", plot)), 1) << plot;
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#slice-images canvas').length;"), 1);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#spheres canvas').length;"), 2);  // the spheres stay
}

// The lit sphere: a press on it brings the light from the direction of the sphere's point there —
// at (½, ½) of the disc's radius, θ = 45°, φ = 45° — which moves the sliders and every view.
TEST_F(Page, APressOnASphereMovesTheLightInEveryView) {
  open(kState);
  const std::string polar_before = browser_->run("return document.querySelector('#plot-polar line.incident').getAttribute('x2');").get<std::string>();
  const auto lobe3d = [&] {
    return browser_->run("const c = document.getElementById('lobe3d'), copy = document.createElement('canvas');"
                         "copy.width = c.width; copy.height = c.height; const x = copy.getContext('2d'); x.drawImage(c, 0, 0);"
                         "return Array.from(x.getImageData(0, 0, c.width, c.height).data).join(',');").get<std::string>();
  };
  const std::string lobe3d_before = lobe3d();
  const int done = renders();
  browser_->run(
      "const c = document.getElementById('sphere-0'), b = c.getBoundingClientRect();"
      "c.dispatchEvent(new PointerEvent('pointerdown', {clientX: b.left + 0.75 * b.width, clientY: b.top + 0.25 * b.height,"
      "                                                 buttons: 1, bubbles: true}));");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  EXPECT_EQ(state()["theta"], 45);
  EXPECT_EQ(state()["phi"], 45);
  EXPECT_EQ(browser_->run("return document.getElementById('light-theta').value;"), "45");
  EXPECT_NE(browser_->run("return document.querySelector('#plot-polar line.incident').getAttribute('x2');").get<std::string>(),
            polar_before);
  EXPECT_NE(lobe3d(), lobe3d_before);  // the 3-D lobe's incident direction and lobes moved
  expect_matches_cpu(0, make_model("log-normalized", {{"n", 50}}), 45, 45);
}

// The sampling view: the first model's sampler at the light's θ_i, its χ² verdict as the API
// gives it, the histograms and the sampled directions drawn.
TEST_F(Page, TheSamplingViewShowsTheChecksVerdict) {
  json page = kState;
  page["samplingSamples"] = 20000;
  open(page);
  const std::string verdict = browser_->run("return document.getElementById('sampling-verdict').textContent;").get<std::string>();
  const json c = json::parse(specula::testing::post(server_.port(), "/api/sampling",
                                  json{{"model", "log-normalized"}, {"params", {{"n", 50}}}, {"theta", 30}, {"samples", 20000},
                                       {"bins", 16}, {"points", 1500}}.dump()).body);
  EXPECT_THAT(verdict, HasSubstr(fmt::format("with {} degrees of freedom", c["dof"].get<int>())));
  EXPECT_THAT(verdict, HasSubstr("passes"));
  EXPECT_EQ(browser_->run("return document.getElementById('sampling-observed').width;"), 32);
  // The observed heat map is not blank, and the disc has points on it.
  EXPECT_GT(browser_->run("const c = document.getElementById('sampling-observed');"
                          "return Math.max(...c.getContext('2d').getImageData(0, 0, c.width, c.height).data.filter((_, i) => i % 4 === 0));")
                .get<int>(), 100);
  EXPECT_GT(browser_->run("const c = document.getElementById('sampling-points');"
                          "return c.getContext('2d').getImageData(0, 0, c.width, c.height).data.filter((v, i) => i % 4 === 0 && v === 255).length;")
                .get<int>(), 50);
}

/// How many of the canvas's pixels are red (r ≫ g ≈ b: not the amber of the incident line) and blue
/// (b ≫ r, g).
std::pair<int, int> red_and_blue_pixels(WebDriver& browser, const std::string& id) {
  const json counts = browser.run(
      "const c = document.getElementById(arguments[0]), copy = document.createElement('canvas');"
      "copy.width = c.width; copy.height = c.height; const x = copy.getContext('2d'); x.drawImage(c, 0, 0);"
      "const d = x.getImageData(0, 0, c.width, c.height).data; let red = 0, blue = 0;"
      "for (let i = 0; i < d.length; i += 4) { if (d[i] > d[i + 1] + 40 && Math.abs(d[i + 1] - d[i + 2]) < 30) ++red;"
      "  if (d[i + 2] > d[i] + 40 && d[i + 2] > d[i + 1] + 20) ++blue; }"
      "return [red, blue];",
      json::array({id}));
  return {counts[0].get<int>(), counts[1].get<int>()};
}

// The 3-D lobe: one colour per model, scaled by the largest f the API gives over the hemisphere;
// a drag turns it, the wheel zooms, and a new light angle reshapes it.
TEST_F(Page, TheThreeDLobeShowsEveryModelAndTurnsWithTheMouse) {
  open(kState);
  EXPECT_GT(red_and_blue_pixels(*browser_, "lobe3d").first, 200);  // log-normalized, the larger lobe
  double largest = 0;
  for (const auto& [id, n] : {std::pair{"log-normalized", 50}, std::pair{"schlick", 20}}) {
    const json grid = json::parse(specula::testing::post(server_.port(), "/api/hemisphere",
                                                         json{{"model", id}, {"params", {{"n", n}}}, {"theta_i", 30}}.dump()).body);
    for (const auto& row : grid["values"])
      for (const auto& v : row) largest = std::max(largest, v.is_number() ? v.get<double>() : 0.0);
  }
  const auto shown = [&](const char* key) {
    return std::stod(browser_->run(fmt::format("return document.getElementById('lobe3d').dataset.{};", key)).get<std::string>());
  };
  EXPECT_NEAR(shown("largest"), largest, 1e-9 * largest);
  browser_->run(
      "const c = document.getElementById('lobe3d'), b = c.getBoundingClientRect(), x = b.left + b.width / 2, y = b.top + b.height / 2;"
      "c.dispatchEvent(new PointerEvent('pointerdown', {clientX: x, clientY: y, buttons: 1, bubbles: true}));"
      "c.dispatchEvent(new PointerEvent('pointermove', {clientX: x + 40, clientY: y + 10, buttons: 1, bubbles: true}));"
      "c.dispatchEvent(new PointerEvent('pointerup', {clientX: x + 40, clientY: y + 10, bubbles: true}));"
      "c.dispatchEvent(new WheelEvent('wheel', {deltaY: 100, bubbles: true, cancelable: true}));");
  EXPECT_NEAR(shown("yaw"), 10, 1e-9);
  EXPECT_NEAR(shown("pitch"), 30, 1e-9);
  EXPECT_NEAR(shown("distance"), 3.3, 1e-9);
  const auto pixels = [&] {
    return browser_->run("const c = document.getElementById('lobe3d'), copy = document.createElement('canvas');"
                         "copy.width = c.width; copy.height = c.height; const x = copy.getContext('2d'); x.drawImage(c, 0, 0);"
                         "return Array.from(x.getImageData(0, 0, c.width, c.height).data).join(',');").get<std::string>();
  };
  const std::string before = pixels();
  int done = renders();
  browser_->send_keys("#light-theta", std::string(kArrowLeft) + kArrowLeft + kArrowLeft + kArrowLeft + kArrowLeft);
  ASSERT_TRUE(wait_until_rendered(done + 1));
  EXPECT_NE(pixels(), before);  // θ_i = 25°: the lobes lean elsewhere
  done = renders();
  browser_->click("#visible-0");  // schlick alone: blue
  ASSERT_TRUE(wait_until_rendered(done + 1));
  const auto [red, blue] = red_and_blue_pixels(*browser_, "lobe3d");
  EXPECT_LT(red, 10);
  EXPECT_GT(blue, 200);
}

// The lit object: the server's progressive render reaches its sample count; a malformed OBJ upload
// is refused in one line and the page goes on; a good one renders.
TEST_F(Page, TheLitObjectRefinesItsImageAndTakesUploads) {
  json page = kState;
  page["lit"] = {{"model", 0}, {"obj", "sphere"}, {"probe", "furnace"}, {"estimator", "mis"}, {"samples", 64}, {"exposure", 0}};
  open(page);
  ASSERT_TRUE(browser_->wait_for("const i = document.getElementById('lit-image'); return i.dataset.state === 'done' && i.complete;"));
  EXPECT_EQ(browser_->run("return document.getElementById('lit-image').dataset.samples;"), "64");
  EXPECT_EQ(browser_->run("return document.getElementById('lit-image').naturalWidth;"), 160);
  EXPECT_THAT(browser_->run("return document.getElementById('lit-counter').textContent;").get<std::string>(),
              HasSubstr("64 of 64 samples per pixel"));
  const auto dir = std::filesystem::temp_directory_path();
  const auto bad = dir / fmt::format("specula-bad-{}.obj", ::getpid()), good = dir / fmt::format("specula-good-{}.obj", ::getpid());
  std::ofstream(bad) << "v 0 0 0\nf 1 2 3\n";
  std::ofstream(good) << "v -1 -1 0\nv 1 -1 0\nv 0 1 0\nv 0 0 1\nf 1 2 4\nf 2 3 4\nf 3 1 4\nf 1 3 2\n";
  browser_->send_keys("#lit-upload-obj", bad.string());
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('status').textContent.includes('refers to vertex 2');"));
  EXPECT_EQ(browser_->run("return document.getElementById('lit-obj').value;"), "sphere");
  browser_->send_keys("#lit-upload-obj", good.string());
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('lit-obj').value.startsWith('obj-');"));
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('lit-caption').textContent.includes('uploaded mesh')"
                                 " && document.getElementById('lit-image').dataset.state === 'done';"));
  std::filesystem::remove(bad);
  std::filesystem::remove(good);
  EXPECT_EQ(state()["lit"]["obj"].get<std::string>().substr(0, 4), "obj-");
}

// BRDF Explorer's channels: a parameter given per channel ([R, G, B]) makes the sphere a composite
// of the three channels' renders, as `render -p NAME=R,G,B` does; the plots follow the channel the
// page picks, the luminance being the Rec. 709 sum of the channels' values. And the energy view's
// compensations against the random walk, which this GGX model has.
TEST_F(Page, ParametersPerChannelColourTheSphereAndThePlotsFollowTheChannel) {
  const std::vector<double> eta{0.2, 0.9, 1.1}, kappa{3.9, 2.4, 1.9};
  json page = kState;
  page["models"] = {{{"id", "ggx-conductor"}, {"params", {{"alpha", 0.3}, {"eta", eta}, {"kappa", kappa}}}}};
  open(page);
  std::vector<std::vector<std::uint8_t>> channels;
  for (std::size_t c = 0; c < 3; ++c)
    channels.push_back(cpu_image(make_model("ggx-conductor", {{"alpha", 0.3}, {"eta", eta[c]}, {"kappa", kappa[c]}}), 30, 135));
  std::vector<std::uint8_t> composite(channels[0].size());
  for (std::size_t i = 0; i < composite.size(); ++i) composite[i] = channels[i % 3][i];
  const Agreement a = compare(sphere_pixels(0), composite);
  EXPECT_GE(a.within_2, 0.999) << "max difference " << a.max_difference;
  EXPECT_GT(compare(sphere_pixels(0), channels[1]).max_difference, 20);  // control: one channel's render alone

  const auto largest = [&](const std::vector<double>& weights) {
    std::vector<double> sum;
    for (std::size_t c = 0; c < 3; ++c) {
      const json grid = json::parse(specula::testing::post(server_.port(), "/api/hemisphere",
          json{{"model", "ggx-conductor"}, {"params", {{"alpha", 0.3}, {"eta", eta[c]}, {"kappa", kappa[c]}}}, {"theta_i", 30}}.dump()).body);
      std::size_t k = 0;
      for (const auto& row : grid["values"])
        for (const auto& v : row) {
          if (sum.size() <= k) sum.push_back(0);
          sum[k++] += weights[c] * (v.is_number() ? v.get<double>() : 0.0);
        }
    }
    return *std::max_element(sum.begin(), sum.end());
  };
  const auto shown = [&] { return std::stod(browser_->run("return document.getElementById('lobe3d').dataset.largest;").get<std::string>()); };
  const double luminance = largest({0.2126, 0.7152, 0.0722});
  EXPECT_NEAR(shown(), luminance, 1e-9 * luminance);
  const int done = renders();
  browser_->run("const s = document.getElementById('channel'); s.value = 'r'; s.dispatchEvent(new Event('change'));");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  const double red = largest({1, 0, 0});
  EXPECT_NEAR(shown(), red, 1e-9 * red);
  EXPECT_GT(std::abs(red - luminance), 1e-3 * red);  // the channels differ: the check can tell them apart
  EXPECT_EQ(state()["channel"], "r");
  EXPECT_EQ(browser_->run("return document.getElementById('param-0-eta-b') !== null && document.getElementById('param-rgb-0-eta').checked;"), true);
  // The energy view's compensations against the walk, for this GGX model in the red channel's parameters.
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('plot-compensation').dataset.model === 'ggx-conductor';"));
  const std::string caption = browser_->run("return document.getElementById('compensation-caption').textContent;").get<std::string>();
  EXPECT_THAT(caption, HasSubstr("ggx+ms"));
  EXPECT_THAT(caption, HasSubstr("kulla-conty"));
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-compensation polyline').length;"), 10);  // 8 schemes, the walk's band

  // The θ_h × θ_d image's chroma toggle: each channel of the image from its own parameters.
  int before = renders();
  browser_->click("#slice-chroma");
  ASSERT_TRUE(wait_until_rendered(before + 1));
  EXPECT_EQ(browser_->run("return document.getElementById('slice-0').dataset.chroma;"), "true");
  const json rgba = browser_->run("const c = document.getElementById('slice-0');"
                                  "return Array.from(c.getContext('2d').getImageData(0, 0, c.width, c.height).data);");
  int worst = 0, spread = 0;
  for (std::size_t c = 0; c < 3; ++c) {
    const auto expected = slice_image(make_model("ggx-conductor", {{"alpha", 0.3}, {"eta", eta[c]}, {"kappa", kappa[c]}}), 90, 0, 2.2);
    for (std::size_t p = 0; p < expected.size(); ++p) {
      worst = std::max(worst, std::abs(rgba[4 * p + c].get<int>() - expected[p]));
      spread = std::max(spread, std::abs(rgba[4 * p].get<int>() - rgba[4 * p + 2].get<int>()));
    }
  }
  EXPECT_LE(worst, 1);
  EXPECT_GT(spread, 16);  // in colour: R and B differ

  // The θ_o plot's viewer azimuth: out of the plane of incidence, another curve.
  const double top = lobe_plot_top(*browser_);
  before = renders();
  browser_->run("const s = document.getElementById('plot-phi-v'); s.value = '90'; s.dispatchEvent(new Event('input'));");
  ASSERT_TRUE(wait_until_rendered(before + 1));
  EXPECT_EQ(state()["phiV"], 90);
  EXPECT_NE(lobe_plot_top(*browser_), top);
}

// Saved sessions: the page's own models as a model file the CLI reads, the state as a settings
// file; loading that file brings the page back as it was saved.
TEST_F(Page, ASavedSessionIsAModelFileAndLoadsBackIdentically) {
  const json definition = {{"id", "my-lobe"}, {"name", "mine"}, {"kind", "lobe"}, {"lobe", "max(0, 1 - n*(1-c)/4)^4"},
                           {"form", "rv"}, {"normalization", "quadrature"},
                           {"params", {{"n", {{"default", 20}, {"min", 0}, {"max", 1e6}, {"min_exclusive", true}}}}}};
  json saved = kState;
  saved["models"] = {{{"id", "my-lobe"}, {"definition", definition}, {"params", {{"n", 30}}}},
                     {{"id", "ggx"}, {"params", {{"alpha", 0.4}}}}};
  saved["theta"] = 44;
  open(saved);
  browser_->click("#session-save");
  const auto text = [&](const char* id) {
    return browser_->run(fmt::format("return fetch(document.getElementById('{}').href).then((r) => r.text());", id)).get<std::string>();
  };
  const auto infos = parse_model_file(text("session-toml"), "session");
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_EQ(infos[0].id, "my-lobe");
  EXPECT_EQ(infos[0].params.at(0).default_value, 20);
  const std::string settings = text("session-json");
  const json state_saved = state();
  EXPECT_EQ(json::parse(settings)["models"], state_saved["models"]);

  open(kState);  // another view, then the file
  const auto bad = std::filesystem::temp_directory_path() / fmt::format("specula-not-a-session-{}.json", ::getpid());
  std::ofstream(bad) << R"({"models": "none"})";
  browser_->send_keys("#session-load", bad.string());  // refused in one line; the page keeps its view
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('status').textContent.startsWith('session: ');"));
  std::filesystem::remove(bad);
  EXPECT_EQ(state()["theta"], 30);
  const auto path = std::filesystem::temp_directory_path() / fmt::format("specula-session-{}.json", ::getpid());
  std::ofstream(path) << settings;
  browser_->send_keys("#session-load", path.string());
  ASSERT_TRUE(browser_->wait_for("return (new URLSearchParams(location.hash.slice(1)).get('state') || '').includes('\"theta\":44')"
                                 " && document.getElementById('status').textContent === 'ready';"));
  std::filesystem::remove(path);
  EXPECT_EQ(state(), state_saved);
  EXPECT_TRUE(browser_->wait_for("return document.getElementById('sphere-1') !== null;"));
}

// The fit panel's tests fit k(n) at 10 values of n, not the paper's 50: the panel is what they
// check, and a fit's cost under the sanitizers grows with the rows (58 s → 23 s for the two).
// For the same reason the page's requests to /api/fit ask for the smallest search (one island of
// 20, enumeration to size 5; the panel has no fields for these): the default enumeration of
// 20 000 forms was 11 s of each fit and showed the panel nothing more.
void set_small_fit(WebDriver& browser, int generations) {
  browser.run(fmt::format("document.getElementById('fit-generations').value = '{}';", generations));
  browser.run("document.getElementById('fit-n').value = '1:100@10:log';");
  browser.run(
      "const fetched = window.fetch;"
      "window.fetch = (path, init) => {"
      "  if (path === '/api/fit' && init && init.body)"
      "    init = {...init, body: JSON.stringify({...JSON.parse(init.body), islands: 1, population: 20, enumerate_size: 5})};"
      "  return fetched(path, init);"
      "};");
}

TEST_F(Page, TheFitPanelShowsTheFrontWithCopyableCode) {
  open(kState);
  set_small_fit(*browser_, 3);
  browser_->click("#fit-start");
  ASSERT_TRUE(browser_->wait_for("return /: (done|failed)/.test(document.getElementById('fit-status').textContent);"));
  EXPECT_THAT(browser_->run("return document.getElementById('fit-status').textContent;").get<std::string>(), HasSubstr("done"));
  EXPECT_GE(browser_->run("return document.querySelectorAll('#fit-front tbody tr').length;").get<int>(), 3);
  EXPECT_THAT(browser_->run("return document.querySelector('#fit-front tr.chosen').textContent;").get<std::string>(),
              HasSubstr("chosen"));
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#fit-front tbody button').length;"),
            2 * browser_->run("return document.querySelectorAll('#fit-front tbody tr').length;").get<int>());
}

// The snap switch reaches the server: its status says which it ran.
TEST_F(Page, TheFitPanelsSnapSwitchReachesTheServer) {
  open(kState);
  set_small_fit(*browser_, 2);
  EXPECT_EQ(browser_->run("return document.getElementById('fit-snap').checked;"), true);
  browser_->click("#fit-start");
  ASSERT_TRUE(browser_->wait_for("return /: (done|failed)/.test(document.getElementById('fit-status').textContent);"));
  EXPECT_THAT(browser_->run("return document.getElementById('fit-status').textContent;").get<std::string>(),
              HasSubstr("constants snapped"));
  browser_->run("document.getElementById('fit-snap').checked = false;");
  browser_->click("#fit-start");
  ASSERT_TRUE(browser_->wait_for("return /constants as fitted/.test(document.getElementById('fit-status').textContent) && "
                                 "/: (done|failed)/.test(document.getElementById('fit-status').textContent);"));
}

// The designer panel: a small search's front, references set apart, and one click puts a member
// on the page as a model card with its sphere. The page's request asks for the first two shapes
// (max_forms, which the panel has no field for; F = c and F = c², no laws): the panel is what this
// checks, and all eight shapes of the search took 17-24 s under the sanitizers.
TEST_F(Page, TheDesignPanelAddsAMemberToThePagesModels) {
  open(kState);
  browser_->run(
      "const fetched = window.fetch;"
      "window.fetch = (path, init) => {"
      "  if (path === '/api/design' && init && init.body)"
      "    init = {...init, body: JSON.stringify({...JSON.parse(init.body), max_forms: 2})};"
      "  return fetched(path, init);"
      "};");
  for (const auto& [id, value] : {std::pair{"design-lo", "1"}, {"design-hi", "100"}, {"design-ops", "fma,mul"},
                                  {"design-cost", "2"}, {"design-time", "10"}})
    browser_->run(fmt::format("document.getElementById('{}').value = '{}';", id, value));
  browser_->run("document.getElementById('design-timing').checked = false;");
  browser_->click("#design-start");
  ASSERT_TRUE(browser_->wait_for("return /: (done|stopped|failed)/.test(document.getElementById('design-status').textContent);", 300));
  EXPECT_THAT(browser_->run("return document.getElementById('design-status').textContent;").get<std::string>(), HasSubstr(": done"));
  const int members = browser_->run("return document.querySelectorAll('#design-front tbody tr.member').length;").get<int>();
  ASSERT_GT(members, 0);
  EXPECT_GE(browser_->run("return document.querySelectorAll('#design-front tbody tr.reference').length;").get<int>(), 2);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#design-front tbody button').length;").get<int>(), members);
  const std::string id = browser_->run("return document.querySelector('#design-front tr.member td').textContent;").get<std::string>();
  int done = renders();
  browser_->click("#design-front tr.member button");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('sphere-2') !== null;"));
  EXPECT_EQ(state()["models"][2]["id"], id + "-normalized");
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#checks tbody tr').length;"), 3);
  // The front's chart: a point per lobe, the members' clickable; a click adds one as the table's button does.
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#design-chart circle.member[role=button]').length;").get<int>(), members);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#design-chart circle.reference').length;").get<int>(), 0);  // untimed
  done = renders();
  browser_->run("document.querySelector('button[aria-label=\"Remove model 3\"]').click();");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  ASSERT_EQ(state()["models"].size(), 2u);
  done = renders();
  browser_->run("document.querySelector('#design-chart circle.member').dispatchEvent(new MouseEvent('click'));");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('sphere-2') !== null;"));
  EXPECT_EQ(state()["models"][2]["id"], id + "-normalized");
}

/// The editor's default definition as a model file, for the CPU renderer's image of it.
Model editor_default_model() {
  const auto infos = parse_model_file(R"([[model]]
id = "my-lobe"
name = "the editor's default"
kind = "lobe"
form = "rv"
lobe = "max(0, 1 - n*(1-c)/4)^4"
normalization = "quadrature"
[model.params.n]
default = 20
min = 0
min_exclusive = true
max = 1e6
)", "editor");
  return make_model(std::make_shared<const ModelInfo>(infos.front()));
}

TEST_F(Page, TheEditorAddsAModelCardWithItsSphere) {
  open(kState);
  const int done = renders();
  browser_->click("#editor-apply");
  ASSERT_TRUE(wait_until_rendered(done + 1));
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('sphere-2') !== null;"));
  EXPECT_EQ(browser_->run("return document.getElementById('editor-error').textContent;"), "");
  EXPECT_EQ(state()["models"][2]["id"], "my-lobe");
  EXPECT_EQ(browser_->run("return document.getElementById('model-2').value;"), "my-lobe");
  expect_matches_cpu(2, editor_default_model(), 30, 135);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-albedo polyline').length;"), 3);
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#checks tbody tr').length;"), 3);
  // The views added for issue 40 take the user's model as a built-in's: the 3-D lobe (its values
  // by the same definition) and the lit object.
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#slice-images canvas').length;"), 3);
  browser_->run("const s = document.getElementById('lit-model'); s.value = '2'; s.dispatchEvent(new Event('change'));");
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('lit-caption').textContent.startsWith('my-lobe')"
                                 " && document.getElementById('lit-image').dataset.samples > 0;"));
  EXPECT_EQ(state()["lit"]["model"], 2);
}

TEST_F(Page, TheEditorAppliesWhenTypingPauses) {
  open(kState);
  const int done = renders();
  EXPECT_EQ(state()["models"].size(), 2u);  // nothing applied before the typing
  browser_->run("document.getElementById('editor-formula').value = '';");
  browser_->send_keys("#editor-formula", "max(0, 1 - n*(1-c)/4)^4");  // no click on Apply
  ASSERT_TRUE(wait_until_rendered(done + 1));
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('sphere-2') !== null;"));
  expect_matches_cpu(2, editor_default_model(), 30, 135);
}

TEST_F(Page, TheEditorShowsTheServersErrorNextToTheFormula) {
  open(kState);
  browser_->run("document.getElementById('editor-formula').value = '';");
  browser_->send_keys("#editor-formula", "c^n + x");
  browser_->click("#editor-apply");
  ASSERT_TRUE(browser_->wait_for("return document.getElementById('editor-error').textContent !== '';"));
  const std::string error = browser_->run("return document.getElementById('editor-error').textContent;").get<std::string>();
  EXPECT_THAT(error, HasSubstr("model.lobe: column 7: unknown variable 'x'"));
  EXPECT_EQ(browser_->run("return document.getElementById('editor-formula').getAttribute('aria-invalid');"), "true");
  EXPECT_EQ(state()["models"].size(), 2u);  // no card for a definition the server refused
  EXPECT_EQ(browser_->run("return document.getElementById('status').textContent;"), "ready");
}

// A busy server (one computing place: the page's parallel requests get 503 with Retry-After) is
// asked again, and the page still gets to ready with every view drawn.
TEST_F(Page, ABusyServerIsAskedAgainUntilThePageIsReady) {
  Limits limits;
  limits.max_busy_requests = 1;
  limits.busy_wait_seconds = 0.05;
  TestServer busy(limits);
  browser_->go(fmt::format("http://127.0.0.1:{}/#state={}", busy.port(), percent_encoded(kState.dump())));
  ASSERT_TRUE(wait_until_rendered(1)) << browser_->run("return document.getElementById('status').textContent;");
  EXPECT_EQ(browser_->run("return document.querySelectorAll('#plot-lobe polyline').length;"), 2);
}

TEST_F(Page, FitsAPhoneWidthScreen) {
  browser_->session("POST", "/window/rect", {{"width", 390}, {"height", 844}});
  open(kState);
  const int viewport = browser_->run("return document.documentElement.clientWidth;").get<int>();
  EXPECT_LE(browser_->run("return document.documentElement.scrollWidth;").get<int>(), viewport);
}

}  // namespace
}  // namespace specula::serve
