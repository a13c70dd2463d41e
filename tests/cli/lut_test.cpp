// specula lut and the M+ms models through the CLI: formats, layout, bad input (exit 2, one line),
// atomic output, Ctrl-C; each with a negative control.
#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "text_support.h"

namespace specula::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST_F(Cli, LutCsvHasOneRowPerCellWithTheAverageOnEachRowOfItsParameter) {
  const Result r = ok({"lut", "--model", "lambert", "--sweep", "rho=0.25,0.5", "--mu", "0.5,1", "--average", "--round", "6"});
  EXPECT_THAT(lines_of(r.out), ElementsAre("rho,mu,E,E_avg", "0.25,0.5,0.250000,0.250000", "0.25,1,0.250000,0.250000",
                                           "0.5,0.5,0.500000,0.500000", "0.5,1,0.500000,0.500000"));
  // Without --sweep and --average: one row at the model's values, no E_avg column.
  EXPECT_THAT(lines_of(ok({"lut", "--model", "lambert", "-p", "rho=0.5", "--mu", "1", "--round", "3"}).out),
              ElementsAre("mu,E", "1,0.500"));
}

TEST_F(Cli, LutJsonNamesTheModelAndColumns) {
  const auto json = nlohmann::json::parse(ok({"lut", "--model", "lambert", "--mu", "1", "--format", "json"}).out);
  EXPECT_EQ(json["model"], "lambert");
  EXPECT_EQ(json["columns"], nlohmann::json::array({"mu", "E"}));
  EXPECT_NEAR(json["rows"][0]["E"].get<double>(), 1, 1e-12);
}

TEST_F(Cli, LutCodeStatesItsInterpolationErrorAndHasTheLookup) {
  const Result cpp = ok({"lut", "--model", "ggx", "--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@4", "--average", "--format", "cpp"});
  EXPECT_THAT(cpp.out, HasSubstr("Bilinear interpolation error, max |lookup - cubature| at the cells' centres: "));
  EXPECT_THAT(cpp.out, HasSubstr("inline constexpr float kE[kPCount * kMuCount] = {"));
  EXPECT_THAT(cpp.out, HasSubstr("inline float energy(float mu, float p) {"));
  EXPECT_THAT(cpp.out, HasSubstr("inline float energy_average(float p) {"));
  const Result glsl = ok({"lut", "--model", "ggx", "--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@4", "--format", "glsl"});
  EXPECT_THAT(glsl.out, HasSubstr("const float specula_lut_E[12] = float[12]("));
  EXPECT_THAT(glsl.out, HasSubstr("float specula_lut_energy(float mu, float p) {"));
  EXPECT_EQ(glsl.out.find("energy_average"), std::string::npos);  // no --average, no E_avg
}

// The code's header comment quotes the command line and the model: an inline formula's newline
// stays in the comment, where "* pwned" on a line of its own would not compile.
TEST_F(Cli, LutCodeKeepsAnInlineFormulaInItsComments) {
  for (const char* format : {"cpp", "glsl"}) {
    const Result r = ok({"lut", "--model", "brdf: rho/pi\n* pwned", "-p", "pwned=1", "--mu", "0.5,1", "--format", format});
    EXPECT_TRUE(only_in_comments(r.out, "pwned")) << r.out;
    EXPECT_THAT(r.out, HasSubstr("// specula lut --model brdf: rho/pi * pwned -p pwned=1")) << r.out;
  }
  EXPECT_FALSE(only_in_comments("// brdf: rho/pi\n* pwned\n", "pwned"));  // the negative control of the check
}

TEST_F(Cli, LutImagesAreMuAlongXAndTheParameterAlongY) {
  const fs::path png = work() / "e.png", exr = work() / "e.exr";
  ok({"lut", "--model", "ggx", "--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@4", "--format", "png16", "-o", png.string(), "-q"});
  const std::string bytes = bytes_of(png);
  ASSERT_GT(bytes.size(), 26u);
  // IHDR: width 4, height 3, bit depth 16, colour type 0 (gray).
  EXPECT_EQ(bytes.substr(16, 8), std::string("\0\0\0\4\0\0\0\3", 8));
  EXPECT_EQ(bytes[24], 16);
  EXPECT_EQ(bytes[25], 0);
  EXPECT_THAT(bytes, HasSubstr("E = code / 65535 * 1"));
  ok({"lut", "--model", "ggx", "--mu", "0.25:1@4", "--format", "exr", "-o", exr.string()});
  EXPECT_EQ(bytes_of(exr).substr(0, 4), std::string("\x76\x2f\x31\x01", 4));
}

TEST_F(Cli, LutBadInputIsExitTwoWithOneLine) {
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--mu", "0"}).err, HasSubstr("--mu: 0 is outside [1e-09, 1]"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--mu", "0.5,0.25"}).err, HasSubstr("values must increase"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--sweep", "beta=1,2"}).err, HasSubstr("no parameter 'beta'"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--sweep", "alpha=0.1,0.2", "-p", "alpha=0.3"}).err,
              HasSubstr("also given as --param"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--sweep", "alpha"}).err, HasSubstr("expected NAME=LIST"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--sweep", "alpha=0.1:1@300", "--mu", "0.1:1@300"}).err,
              HasSubstr("more than 65536"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--sweep", "alpha=0.1:1@257", "--mu", "1", "--average"}).err,
              HasSubstr("--average: 257 values of alpha is more than 256"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--mu", "0.1,0.2,0.5", "--format", "glsl"}).err, HasSubstr("evenly spaced"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--format", "png16"}).err, HasSubstr("needs --out"));
  bad({"lut", "--model", "ggx", "--format", "tiff"});
  bad({"lut", "--model", "no-such+ms"});
  // Negative controls: the same command with a valid μ succeeds, and 256 averages are allowed.
  ok({"lut", "--model", "lambert", "--mu", "0.5"});
  ok({"lut", "--model", "lambert", "--sweep", "rho=0.1:1@256", "--mu", "1", "--average", "-q"});
}

TEST_F(Cli, LutOutputIsAtomicAndCtrlCLeavesNoFile) {
  const fs::path out = work() / "e.csv";
  bad({"lut", "--model", "ggx", "--mu", "0", "-o", out.string()});
  EXPECT_THAT(listing(work()), IsEmpty());
  const pid_t pid = start({"lut", "--model", "ggx", "--sweep", "alpha=0.01:1@200", "--mu", "0.001:1@200", "-q", "-o", out.string()});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ::kill(pid, SIGINT);
  const Result r = finish(pid);
  EXPECT_EQ(r.code, 128 + SIGINT) << r;
  EXPECT_THAT(listing(work()), IsEmpty());
  // Negative control: a run that finishes leaves exactly the file.
  ok({"lut", "--model", "lambert", "--mu", "1", "-o", out.string()});
  EXPECT_THAT(listing(work()), ElementsAre("e.csv"));
}

TEST_F(Cli, CheckShowsThatGgxMsHasAlbedoOne) {
  const Result r = ok({"check", "--model", "ggx+ms", "--pairs", "500", "--step", "5"});
  EXPECT_THAT(r.out, HasSubstr("energy compensation         albedo 1 within the table's error"));
  EXPECT_THAT(r.out, HasSubstr("energy conservation         holds"));
  // Negative control: the base model has no such line.
  EXPECT_EQ(ok({"check", "--model", "ggx", "--pairs", "500", "--step", "5"}).out.find("energy compensation"), std::string::npos);
}

}  // namespace
}  // namespace specula::testing
