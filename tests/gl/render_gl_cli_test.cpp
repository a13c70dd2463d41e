// `specula render --backend gl` as a program: a PNG that matches the CPU backend's, with the
// backend and the GL renderer in its metadata and on stderr with --verbose.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fmt/format.h>

#include "../render/render_support.h"
#include "specula/render/image_io.h"
#include "text_support.h"

namespace specula::render {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using specula::testing::TempDir;

struct CliRun {
  int exit_code;
  std::string err;
};

CliRun run_render(const TempDir& dir, const std::string& arguments) {
  const auto err = dir / "stderr.txt";
  const int status = std::system(fmt::format("'{}' render {} 2>'{}'", SPECULA_CLI, arguments, err.string()).c_str());
  CliRun run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, specula::testing::read_file(err)};
  std::filesystem::remove(err);
  return run;
}

std::string get(const Metadata& metadata, const std::string& key) {
  for (const auto& [k, v] : metadata)
    if (k == key) return v;
  return "<missing " + key + ">";
}

TEST(RenderGlCli, WritesAPngLikeTheCpuBackendsAndNamesTheRenderer) {
  TempDir dir;
  const std::string common = "--model log-normalized -p n=50 --size 96x64 --light dir:-1,1,1 --light point:0,3,3 "
                             "--tonemap aces";
  const CliRun gl = run_render(dir, fmt::format("{} --backend gl --verbose --out '{}'", common, (dir / "gl.png").string()));
  ASSERT_EQ(gl.exit_code, 0) << gl.err;
  const CliRun cpu = run_render(dir, fmt::format("{} --out '{}'", common, (dir / "cpu.png").string()));
  ASSERT_EQ(cpu.exit_code, 0) << cpu.err;

  const ImageFile png = read_png(dir / "gl.png");
  EXPECT_EQ(png.image.width(), 96);
  EXPECT_EQ(get(png.metadata, "renderer"), "gl");
  const std::string gl_renderer = get(png.metadata, "gl-renderer");
  EXPECT_THAT(gl_renderer, Not(HasSubstr("<missing")));
  EXPECT_THAT(gl.err, HasSubstr("rendered 96x64"));
  EXPECT_THAT(gl.err, HasSubstr(gl_renderer.substr(0, gl_renderer.find(' '))));
  EXPECT_EQ(get(read_png(dir / "cpu.png").metadata, "gl-renderer"), "<missing gl-renderer>");

  const Image other = read_png(dir / "cpu.png").image;
  int far = 0;  // PNG decodes to linear: compare the 8-bit codes again
  const Display none{};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 96; ++x)
      for (const auto& [a, b] : {std::pair{png.image.at(x, y).r, other.at(x, y).r}, {png.image.at(x, y).g, other.at(x, y).g}})
        far += std::abs(int(to_srgb8(a, none)) - int(to_srgb8(b, none))) > 1;
  EXPECT_LE(far, 6);  // ≤ 0.1 % of 6144 pixels
}

TEST(RenderGlCli, RefusesTooManyLightsInOneLine) {
  TempDir dir;
  std::string lights;
  for (int i = 0; i < 9; ++i) lights += " --light dir:0,0,1";
  const CliRun run = run_render(dir, fmt::format("--model phong --backend gl{} --out '{}'", lights, (dir / "x.png").string()));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_EQ(run.err, "specula: error: the GL renderer takes at most 8 lights; the scene has 9\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(RenderGlCli, CompareOnTheGlBackendMatchesTheCpuPanel) {
  TempDir dir;
  const std::string common = "--models log-normalized,schlick -p n=50 --size 64x64 --diff log-normalized -q";
  for (const char* backend : {"cpu", "gl"}) {
    const int status = std::system(fmt::format("'{}' compare {} --backend {} --out '{}'", SPECULA_CLI, common, backend,
                                               (dir / (std::string(backend) + ".png")).string())
                                       .c_str());
    ASSERT_EQ(WEXITSTATUS(status), 0) << backend;
  }
  const ImageFile gl = read_png(dir / "gl.png"), cpu = read_png(dir / "cpu.png");
  EXPECT_EQ(get(gl.metadata, "renderer"), "gl");
  ASSERT_EQ(gl.image.width(), cpu.image.width());
  ASSERT_EQ(gl.image.height(), cpu.image.height());
  int far = 0;
  const Display none{};
  for (int y = 0; y < gl.image.height(); ++y)
    for (int x = 0; x < gl.image.width(); ++x)
      far += std::abs(int(to_srgb8(gl.image.at(x, y).g, none)) - int(to_srgb8(cpu.image.at(x, y).g, none))) > 1;
  // Images, labels and heat maps alike (the heat maps' shared scale comes from each backend's own images).
  EXPECT_LE(far, gl.image.width() * gl.image.height() / 1000);
}

}  // namespace
}  // namespace specula::render

namespace specula::render {
namespace {

// `specula design` times its front and references on the GPU (here llvmpipe) beside the CPU: the
// front.csv columns gpu_ps_per_eval and gpu_front, the device on stdout, front-gpu.svg. The
// control: --no-gpu-timing leaves the columns empty and writes no GPU chart. (A search of one
// shape, timed: about 8 s under the sanitizers.)
TEST(DesignGpuCli, TimesTheFrontOnTheGpuBesideTheCpu) {
  TempDir dir;
  for (const bool gpu : {true, false}) {
    const auto out = dir / (gpu ? "gpu" : "cpu"), log = dir / "stdout.txt";
    const int status = std::system(fmt::format("'{}' design --target schlick-weight --ops fma --max-cost 1 -q {} --out '{}' >'{}'",
                                               SPECULA_CLI, gpu ? "" : "--no-gpu-timing", out.string(), log.string())
                                       .c_str());
    ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << specula::testing::read_file(log);
    // The reference `exact`'s row ends with its gpu_ps_per_eval, an empty gpu_front and its
    // max_abs_bound (0: the term itself).
    const std::string csv = specula::testing::read_file(out / "front.csv");
    const auto start = csv.find("\nexact,") + 1;
    std::string row = csv.substr(start, csv.find('\n', start) - start);
    ASSERT_TRUE(row.ends_with(",0")) << row;
    row.erase(row.rfind(','));  // now ending with gpu_front's empty field
    row.pop_back();
    const std::string gpu_ps = row.substr(row.rfind(',') + 1);
    EXPECT_EQ(std::filesystem::exists(out / "front-gpu.svg"), gpu);
    if (gpu) {
      EXPECT_THAT(specula::testing::read_file(log), HasSubstr("GPU: ps per evaluation"));
      // Timed: a number, ≥ 0. It is the term's time less an empty shader's, clamped at 0, and a
      // term as cheap as (1 − c)^5 measures 0 when the machine is loaded (make test, 2026-12-07).
      ASSERT_FALSE(gpu_ps.empty()) << row;
      EXPECT_GE(std::strtod(gpu_ps.c_str(), nullptr), 0) << row;
    } else {
      EXPECT_EQ(gpu_ps, "") << row;
      EXPECT_THAT(specula::testing::read_file(log), Not(HasSubstr("GPU:")));
    }
  }
}

}  // namespace
}  // namespace specula::render
