// specula lut and the M+ms models through the CLI: formats, layout, bad input (exit 2, one line),
// atomic output, Ctrl-C; each with a negative control.
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "text_support.h"

namespace specula::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using ::testing::StartsWith;

std::string bytes_of(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

TEST_F(Cli, LutCsvHasOneRowPerCellWithTheAverageOnEachRowOfItsParameter) {
  const Result r = ok({"lut", "--model", "lambert", "--sweep", "rho=0.25,0.5", "--mu", "0.5,1", "--average", "--round", "6"});
  EXPECT_THAT(lines_of(r.out), ElementsAre(StartsWith("# specula lut --model lambert --sweep rho=0.25,0.5 --mu 0.5,1"),
                                           "rho,mu,E,E_avg", "0.25,0.5,0.250000,0.250000", "0.25,1,0.250000,0.250000",
                                           "0.5,0.5,0.500000,0.500000", "0.5,1,0.500000,0.500000"));
  // Without --sweep and --average: one row at the model's values, no E_avg column.
  EXPECT_THAT(lines_of(ok({"lut", "--model", "lambert", "-p", "rho=0.5", "--mu", "1", "--round", "3"}).out),
              ElementsAre(StartsWith("# specula lut"), "mu,E", "1,0.500"));
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

// Every format says where it came from: the command, the version and the SHA-256 of the values,
// the same hash for the same values in every format, another for other values (the control).
TEST_F(Cli, LutFilesSayWhereTheyCameFrom) {
  const std::vector<std::string> table{"lut", "--model", "ggx", "--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@4", "-q"};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = table;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  const std::string csv = ok(with({})).out;
  const std::size_t at = csv.find("sha256 of the values ");
  ASSERT_NE(at, std::string::npos) << csv;
  const std::string sha = csv.substr(at + 21, 64);
  EXPECT_EQ(sha.find_first_not_of("0123456789abcdef"), std::string::npos) << sha;
  EXPECT_THAT(csv, StartsWith("# specula lut --model ggx --sweep alpha=0.2:0.6@3 --mu 0.25:1@4 --format csv; specula "));
  EXPECT_EQ(nlohmann::json::parse(ok(with({"--format", "json"})).out)["sha256"], sha);
  for (const char* format : {"cpp", "glsl", "hlsl"}) EXPECT_THAT(ok(with({"--format", format})).out, HasSubstr(sha)) << format;
  for (const char* format : {"exr", "exr-half", "png16"}) {
    const fs::path image = work() / (std::string("e.") + format);
    ok(with({"--format", format, "-o", image.string()}));
    EXPECT_THAT(bytes_of(image), HasSubstr(sha)) << format;
  }
  EXPECT_THAT(ok(with({"--format", "npy", "-o", (work() / "e.npy").string()})).err, IsEmpty());  // -q: quiet
  const std::string other = ok({"lut", "--model", "ggx", "--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@5", "-q"}).out;
  EXPECT_THAT(other, Not(HasSubstr(sha)));  // the control
}

// NumPy's .npy 1.0: the magic, a header dict padded so the data starts on 64 bytes, then E as
// little-endian doubles of shape (p, mu), the CSV's values exactly.
TEST_F(Cli, LutNpyIsNumpysFormatWithTheCsvsValues) {
  const fs::path npy = work() / "e.npy";
  const Result r = run({"lut", "--model", "ggx", "--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@4", "--format", "npy", "-o", npy.string()});
  EXPECT_EQ(r.code, 0) << r;
  EXPECT_THAT(r.err, HasSubstr("sha256 of the values"));  // npy's header has no room for it
  const std::string bytes = bytes_of(npy);
  ASSERT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t header = std::size_t(std::uint8_t(bytes[8])) | std::size_t(std::uint8_t(bytes[9])) << 8;
  EXPECT_EQ((10 + header) % 64, 0u);
  EXPECT_THAT(bytes.substr(10, header), StartsWith("{'descr': '<f8', 'fortran_order': False, 'shape': (3, 4), }"));
  ASSERT_EQ(bytes.size(), 10 + header + 12 * 8);
  const auto lines = lines_of(ok({"lut", "--model", "ggx", "--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@4", "-q"}).out);
  ASSERT_EQ(lines.size(), 2u + 12);
  for (std::size_t k = 0; k < 12; ++k) {
    double e;
    std::memcpy(&e, bytes.data() + 10 + header + 8 * k, 8);
    EXPECT_EQ(e, std::stod(lines[2 + k].substr(lines[2 + k].rfind(',') + 1))) << k;
  }
}

// HLSL: the arrays and the lookup compile in glslang's HLSL front end inside a pixel shader; the
// same shader with the lookup misspelt does not (the control).
TEST_F(Cli, LutHlslCompiles) {
  std::string hlsl = ok({"lut", "--model", "ggx", "--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@4", "--average", "--format", "hlsl", "-q"}).out;
  const auto compiles = [&](const std::string& call) {
    const fs::path path = work() / "lut.hlsl";
    std::ofstream(path) << hlsl << "float4 main(float4 pos : SV_Position) : SV_Target { return float4(" << call
                        << ", specula_lut_energy_average(0.3), 0.0, 1.0); }\n";
    const std::string command = "glslangValidator -D -V -e main -S frag " + path.string() + " -o " +
                                (work() / "lut.spv").string() + " > /dev/null 2>&1";
    return std::system(command.c_str()) == 0;
  };
  EXPECT_TRUE(compiles("specula_lut_energy(0.5, 0.3)"));
  EXPECT_FALSE(compiles("specula_lut_energie(0.5, 0.3)"));
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
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--format", "npy"}).err, HasSubstr("needs --out"));
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
