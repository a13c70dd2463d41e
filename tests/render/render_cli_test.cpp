// `specula render` run as a program: images with their metadata, one-line errors with exit code 2
// and no file left behind, --help.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <string>

#include "render_support.h"
#include "specula/render/image_io.h"
#include "text_support.h"

namespace specula::render {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using specula::testing::TempDir;

struct RenderRun {
  int exit_code;
  std::string out, err;
};

// The CLI with `arguments` (shell words, quoted by the caller where needed).
RenderRun run_cli(const TempDir& dir, const std::string& arguments) {
  const auto out = dir.path().parent_path() / (dir.path().filename().string() + ".out");
  const auto err = dir.path().parent_path() / (dir.path().filename().string() + ".err");
  const int status = std::system(fmt::format("'{}' render {} >'{}' 2>'{}'", SPECULA_CLI, arguments,
                                             out.string(), err.string()).c_str());
  RenderRun run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, specula::testing::read_file(out),
          specula::testing::read_file(err)};
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

std::string metadata_value(const Metadata& metadata, const std::string& key) {
  for (const auto& [k, v] : metadata)
    if (k == key) return v;
  return "<missing " + key + ">";
}

// A parameter with three values is a coloured material: each channel is the render of the model
// at that channel's values (the control: channel R is not the render at G's values).
TEST(RenderCli, ThreeValuesOfAParameterRenderEachChannelWithItsOwn) {
  TempDir dir;
  const std::string common = "--model ggx-conductor -p alpha=0.4 --size 12x12 --light dir:1,1,2 --out ";
  const auto render = [&](const std::string& params, const std::string& name) {
    const RenderRun run = run_cli(dir, params + " " + common + "'" + (dir / name).string() + "'");
    EXPECT_EQ(run.exit_code, 0) << run.err;
    return read_exr(dir / name);
  };
  const ImageFile gold = render("-p eta=0.143,0.374,1.442 -p kappa=3.98,2.38,1.60", "gold.exr");
  EXPECT_EQ(metadata_value(gold.metadata, "parameters"), "eta=0.143,0.374,1.442; kappa=3.98,2.38,1.60; alpha=0.4");
  const ImageFile channel[] = {render("-p eta=0.143 -p kappa=3.98", "r.exr"), render("-p eta=0.374 -p kappa=2.38", "g.exr"),
                               render("-p eta=1.442 -p kappa=1.60", "b.exr")};
  double lit = 0, r_against_g = 0;
  for (std::size_t k = 0; k < gold.image.samples().size(); ++k) {
    EXPECT_EQ(gold.image.samples()[k], channel[k % 3].image.samples()[k]) << k;
    lit += gold.image.samples()[k];
    if (k % 3 == 0) r_against_g += std::abs(gold.image.samples()[k] - channel[1].image.samples()[k]);
  }
  EXPECT_GT(lit, 0);
  EXPECT_GT(r_against_g, 1e-3);
}

TEST(RenderCli, AListOfOtherThanThreeValuesIsRefused) {
  TempDir dir;
  const RenderRun run = run_cli(dir, "--model ggx-conductor -p eta=0.1,0.2 --size 8x8 --out '" + (dir / "x.png").string() + "'");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("--param 'eta=0.1,0.2': give one value, or three (R,G,B)"));
  EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST(RenderCli, WritesAPngWithItsSettingsAsText) {
  TempDir dir;
  const RenderRun run = run_cli(dir, fmt::format("--model log-normalized -p n=50 --size 40x30 --light dir:0,0,1 "
                                           "--light point:2,2,3:1,0.5,0.5:9 --tonemap aces --out '{}'",
                                           (dir / "s.png").string()));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, IsEmpty());
  const ImageFile png = read_png(dir / "s.png");
  EXPECT_EQ(png.image.width(), 40);
  EXPECT_EQ(png.image.height(), 30);
  EXPECT_EQ(metadata_value(png.metadata, "model"), "log-normalized");
  EXPECT_EQ(metadata_value(png.metadata, "parameters"), "n=50");
  EXPECT_EQ(metadata_value(png.metadata, "form"), "rv");
  EXPECT_EQ(metadata_value(png.metadata, "renderer"), "cpu");
  EXPECT_EQ(metadata_value(png.metadata, "lights"), "dir:0,0,1:1,1,1:1 point:2,2,3:1,0.5,0.5:9");
  EXPECT_EQ(metadata_value(png.metadata, "tonemap"), "aces");
  EXPECT_GT(png.image.at(20, 15).r, png.image.at(0, 0).r);  // the sphere against the black background
}

TEST(RenderCli, WritesALinearExrAndReportsTimesWhenVerbose) {
  TempDir dir;
  const RenderRun run = run_cli(dir, fmt::format("--model ggx -p alpha=0.2 --size 16x16 --exr-pixel float --verbose --out '{}'",
                                           (dir / "s.exr").string()));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("rendered 16x16"));
  const ImageFile exr = read_exr(dir / "s.exr");
  EXPECT_EQ(metadata_value(exr.metadata, "model"), "ggx");
  EXPECT_EQ(metadata_value(exr.metadata, "parameters"), "alpha=0.2,f0=1");
  EXPECT_EQ(metadata_value(exr.metadata, "form"), "-");
  EXPECT_GT(exr.image.at(8, 8).r, 0);
}

TEST(RenderCli, RendersAnObjMesh) {
  TempDir dir;
  dir.write("quad.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
  const RenderRun run = run_cli(dir, fmt::format("--model phong-normalized --scene '{}' --size 9x9 --light dir:0,0,1 --out '{}'",
                                           (dir / "quad.obj").string(), (dir / "q.png").string()));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_GT(read_png(dir / "q.png").image.at(4, 4).r, 0.1);
}

TEST(RenderCli, BadInputFailsInOneLineWithExitCodeTwoAndNoFile) {
  TempDir dir;
  dir.write("broken.obj", "v 0 0 0\nf 1 2 3\n");
  const auto quoted = [&](const char* name) { return fmt::format("'{}'", (dir / name).string()); };
  const std::string png = quoted("x.png");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--model nope --out " + png, "unknown model"},
      {"--model phong --scene " + quoted("missing.obj") + " --out " + png, "cannot read"},
      {"--model phong --scene " + quoted("broken.obj") + " --out " + png, "cannot read"},
      {"--model phong --size 0x10 --out " + png, "image size 0x10"},
      {"--model phong --size 10 --out " + png, "--size '10'"},
      {"--model phong --out " + quoted("no/x.png"), "cannot write"},
      {"--model phong --out " + quoted("x.jpg"), "unknown image format"},
      {"--model phong --light dir:0,0 --out " + png, "dir:0,0"},
      {"--model phong --diffuse 1,2 --out " + png, "--diffuse"},
      {"--model phong --tonemap aces --out " + quoted("x.exr"), "EXR"},
      {"--model phong -p n=-1 --out " + png, "out of range"},
      {"--model phong --exposure nan --out " + png, "--exposure"},
  };
  for (const auto& [arguments, message] : cases) {
    const RenderRun run = run_cli(dir, arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments;
    EXPECT_THAT(run.err, HasSubstr(message)) << arguments;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }
  EXPECT_THAT(dir.listing(), ElementsAre("broken.obj"));
}

TEST(RenderCli, HelpShowsAnExample) {
  TempDir dir;
  const RenderRun run = run_cli(dir, "--help");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_THAT(run.out, HasSubstr("specula render --model log-normalized"));
  EXPECT_THAT(run.out, HasSubstr("--light"));
}

}  // namespace
}  // namespace specula::render
