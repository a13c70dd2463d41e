// `specula compare` run as a program: the figure's size and metadata, panels identical to what
// `specula render` draws, heat maps against a reference, one summary line per model, and
// one-line errors with exit code 2 and no file left behind.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fmt/format.h>
#include <string>

#include "cli_support.h"
#include "specula/render/image_io.h"
#include "specula/render/panel.h"
#include "text_support.h"

namespace specula::render {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::StartsWith;
using specula::testing::CliRun;
using specula::testing::lines_of;
using specula::testing::run_specula;
using specula::testing::TempDir;

std::string quoted(const std::filesystem::path& path) {
  return fmt::format("'{}'", path.string());
}

std::string panel_metadata(const Metadata& metadata, const std::string& key) {
  for (const auto& [k, v] : metadata)
    if (k == key) return v;
  return "<missing " + key + ">";
}

// The 8-bit code a PNG held, from read_png's linear value.
Srgb8 code_at(const Image& image, int x, int y) {
  const Rgb v = image.at(x, y);
  const auto code = [](double linear) { return static_cast<std::uint8_t>(std::lround(255 * srgb_encode(linear))); };
  return {code(v.r), code(v.g), code(v.b)};
}

// The default layout: margin 16, label height 34, colour bar column 24 + 84 + 34 = 142.
TEST(CompareCli, DefaultsToThePapersThreeModelsSideBySide) {
  TempDir dir;
  const CliRun run = run_specula(dir, "compare --size 24x20 --out " + quoted(dir / "c.png"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const ImageFile png = read_png(dir / "c.png");
  EXPECT_EQ(png.image.width(), 16 + 3 * (24 + 16));
  EXPECT_EQ(png.image.height(), 16 + (20 + 34 + 16));
  EXPECT_EQ(panel_metadata(png.metadata, "models"), "log-normalized,log,schlick");
  EXPECT_EQ(panel_metadata(png.metadata, "parameters"), "log-normalized: n=20; log: n=20; schlick: n=20");
  EXPECT_EQ(panel_metadata(png.metadata, "reference"), "-");
  const auto lines = lines_of(run.out);
  ASSERT_EQ(lines.size(), 3u) << run.out;
  EXPECT_THAT(lines[0], StartsWith("log-normalized (n=20): luminance peak "));
  EXPECT_THAT(lines[2], StartsWith("schlick (n=20): "));
  EXPECT_THAT(run.out, ::testing::Not(HasSubstr("ΔL")));
}

TEST(CompareCli, EachPanelIsWhatRenderDrawsForThatModel) {
  TempDir dir;
  const std::string common = "--size 24x20 -p n=50 --light dir:1,1,2 --tonemap aces --exposure 1";
  ASSERT_EQ(run_specula(dir, fmt::format("compare --models phong-normalized,log {} -q --out {}", common,
                                         quoted(dir / "c.png"))).exit_code, 0);
  ASSERT_EQ(run_specula(dir, fmt::format("render --model log {} --out {}", common, quoted(dir / "r.png"))).exit_code, 0);
  const Image figure = read_png(dir / "c.png").image, single = read_png(dir / "r.png").image;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 24; ++x) ASSERT_EQ(code_at(figure, 16 + 40 + x, 16 + y), code_at(single, x, y)) << x << ',' << y;
}

TEST(CompareCli, DiffAddsHeatMapsAColourBarAndSummaries) {
  TempDir dir;
  const CliRun run = run_specula(dir, "compare -p n=50 --diff log-normalized --size 24x20 --out " + quoted(dir / "d.png"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const ImageFile png = read_png(dir / "d.png");
  EXPECT_EQ(png.image.width(), 16 + 3 * (24 + 16) + 142 + 16);
  EXPECT_EQ(png.image.height(), 16 + 2 * (20 + 34 + 16));
  EXPECT_EQ(panel_metadata(png.metadata, "reference"), "log-normalized");
  EXPECT_GT(std::stod(panel_metadata(png.metadata, "scale_max")), 0);
  // log-normalized against itself: every heat-map pixel is the colour map's 0.
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 24; ++x) ASSERT_EQ(code_at(png.image, 16 + x, 86 + y), viridis_srgb8(0)) << x << ',' << y;
  const auto lines = lines_of(run.out);
  ASSERT_EQ(lines.size(), 3u) << run.out;
  EXPECT_THAT(lines[0], HasSubstr("|ΔL| vs log-normalized: max 0, mean 0"));
  EXPECT_THAT(lines[1], StartsWith("log (n=50): "));
  EXPECT_THAT(lines[1], ::testing::Not(HasSubstr("max 0,")));
}

TEST(CompareCli, ParametersGoToTheModelsThatHaveThem) {
  TempDir dir;
  const CliRun run = run_specula(dir, "compare --models phong,ggx -p n=30 -p alpha=0.2 --size 8x8 -q --out " +
                                          quoted(dir / "p.png"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.out, IsEmpty());
  EXPECT_EQ(panel_metadata(read_png(dir / "p.png").metadata, "parameters"), "phong: n=30; ggx: alpha=0.2,f0=1");
}

TEST(CompareCli, BadInputFailsInOneLineWithExitCodeTwoAndNoFile) {
  TempDir dir;
  const std::string png = quoted(dir / "x.png");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"--models log,nope --out " + png, "unknown model 'nope'"},
      {"--models '' --out " + png, "--models is empty"},
      {"--models log,,schlick --out " + png, "empty model id"},
      {"--size 0x10 --out " + png, "panel size 0x10"},
      {"--size 10 --out " + png, "--size '10'"},
      {"--size 8000x8000 --out " + png, "more than 16384"},
      {"--out " + quoted(dir / "no/x.png"), "cannot write"},
      {"--out " + quoted(dir / "x.exr"), "8-bit PNG"},
      {"--diff nope --out " + png, "unknown model 'nope'"},
      {"--models 'log,lobe: c^' --out " + png, "--models 'lobe: c^': column 9: "},
      {"--diff 'lobe: c^*n' --out " + png, "--diff 'lobe: c^*n': column 9: "},
      {"-p q=3 --out " + png, "--param q"},
      {"--models ggx -p n=3 --out " + png, "--param n"},
      {"-p n=-1 --out " + png, "out of range"},
      {"--scale 1 --out " + png, "--diff"},
      {"--diff log --scale=-1 --out " + png, "--scale -1"},
      {"--exposure nan --out " + png, "--exposure"},
      {"--light dir:0,0 --out " + png, "dir:0,0"},
  };
  for (const auto& [arguments, message] : cases) {
    const bool sized = arguments.find("--size") != std::string::npos;
    const CliRun run = run_specula(dir, (sized ? "compare " : "compare --size 8x8 ") + arguments);
    EXPECT_EQ(run.exit_code, 2) << arguments;
    EXPECT_THAT(run.err, HasSubstr(message)) << arguments;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_THAT(run.out, IsEmpty()) << arguments;
  }
  EXPECT_THAT(dir.listing(), IsEmpty());
}

TEST(CompareCli, HelpShowsAnExample) {
  TempDir dir;
  const CliRun run = run_specula(dir, "compare --help");
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_THAT(run.out, HasSubstr("specula compare -p n=50 --diff log-normalized"));
}

}  // namespace
}  // namespace specula::render
