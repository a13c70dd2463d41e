// specula lut and the M+ms models through the CLI: formats, layout, bad input (exit 2, one line),
// atomic output, Ctrl-C; each with a negative control.
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>

#include "cli_fixture.h"
#include "glsl_support.h"
#include "text_support.h"

namespace specula::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
using ::testing::StartsWith;

/// A command's arguments followed by more.
std::vector<std::string> joined(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

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
  const auto with = [&](const std::vector<std::string>& extra) { return joined(table, extra); };
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

// --schlick-split: E at f0 = 0 and at f0 = 1; with Schlick's F, E is linear in F0, so mixing the
// two gives the cubature's E at any F0 (checked at F0 = 0.3, a table of its own). The control: the
// same mix for cook-torrance-1982, whose Fresnel is the exact dielectric's, is refused, and a mix
// with the ends swapped misses.
TEST_F(Cli, LutSchlickSplitMixesToEveryF0) {
  const std::vector<std::string> grid{"--sweep", "alpha=0.2:0.6@3", "--mu", "0.25:1@4", "--round", "17", "-q"};
  const auto split = lines_of(ok(joined({"lut", "--model", "ggx", "--schlick-split", "--average"}, grid)).out);
  const auto at = lines_of(ok(joined({"lut", "--model", "ggx", "-p", "f0=0.3", "--average"}, grid)).out);
  ASSERT_EQ(split.size(), 2u + 12);
  ASSERT_EQ(at.size(), split.size());
  EXPECT_EQ(split[1], "alpha,mu,E_f0_0,E_f0_1,E_avg_f0_0,E_avg_f0_1");
  const auto cells = [](const std::string& line) {
    std::vector<double> v;
    std::stringstream in(line);
    for (std::string cell; std::getline(in, cell, ',');) v.push_back(std::stod(cell));
    return v;
  };
  double swapped_miss = 0;
  for (std::size_t k = 2; k < split.size(); ++k) {
    const auto s = cells(split[k]), e = cells(at[k]);
    EXPECT_NEAR(s[2] + 0.3 * (s[3] - s[2]), e[2], 1e-12) << split[k];
    EXPECT_NEAR(s[4] + 0.3 * (s[5] - s[4]), e[3], 1e-12) << split[k];
    swapped_miss = std::max(swapped_miss, std::abs(s[3] + 0.3 * (s[2] - s[3]) - e[2]));
  }
  EXPECT_GT(swapped_miss, 0.1);  // the control
  EXPECT_THAT(bad({"lut", "--model", "cook-torrance-1982", "--schlick-split"}).err, HasSubstr("no Schlick Fresnel"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--schlick-split", "-p", "f0=0.5"}).err, HasSubstr("give f0 neither"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--schlick-split", "--sweep", "alpha=0.1:1@200", "--mu", "0.1:1@200"}).err,
              HasSubstr("2 tables of 200 x 200 cells is more than 65536"));
}

// Every format holds both tables: EXR in R and G, png16 one below the other, npy with a first
// axis of 2, code with both lookups and the mix at any F0 (the GLSL compiles; misspelt, not).
TEST_F(Cli, LutSchlickSplitInEveryFormat) {
  const std::vector<std::string> table{"lut", "--model", "ggx", "--schlick-split", "--sweep", "alpha=0.2:0.6@3",
                                       "--mu", "0.25:1@4", "-q"};
  const auto with = [&](const std::vector<std::string>& extra) { return joined(table, extra); };
  const fs::path png = work() / "e.png", exr = work() / "e.exr", npy = work() / "e.npy";
  ok(with({"--format", "png16", "-o", png.string()}));
  EXPECT_EQ(bytes_of(png).substr(16, 8), std::string("\0\0\0\4\0\0\0\6", 8));  // 4 x (2 x 3)
  EXPECT_THAT(bytes_of(png), HasSubstr("rows 0-2: E at f0 = 0, rows 3-5: E at f0 = 1"));
  ok(with({"--format", "exr", "-o", exr.string()}));
  EXPECT_THAT(bytes_of(exr), HasSubstr("R: E at f0 = 0, G: E at f0 = 1"));
  ok(with({"--format", "npy", "-o", npy.string()}));
  EXPECT_THAT(bytes_of(npy), HasSubstr("'shape': (2, 3, 4), }"));
  EXPECT_EQ(bytes_of(npy).size() % 64, (2 * 12 * 8) % 64);
  const std::string cpp = ok(with({"--format", "cpp", "--average"})).out;
  for (const char* part : {"kE_f0_0[kPCount * kMuCount]", "kE_f0_1[kPCount * kMuCount]", "inline float energy(float mu, float p, float f0)",
                           "inline float energy_average(float p, float f0)", "E_f0_1: Bilinear interpolation error"})
    EXPECT_THAT(cpp, HasSubstr(part));
  const std::string glsl = ok(with({"--format", "glsl"})).out;
  const auto compiles = [&](const std::string& call) {
    const std::string shader = "#version 330\n" + glsl + "out vec4 colour;\nvoid main() { colour = vec4(" + call + "); }\n";
    return validate_glsl(shader, "frag").ok;
  };
  EXPECT_TRUE(compiles("specula_lut_energy(0.5, 0.3, 0.04)"));
  EXPECT_FALSE(compiles("specula_lut_energy(0.5, 0.3)"));  // the control: the split's lookup takes F0
}

// Axes spaced for accuracy (a:b@count:powK): the code's lookup interpolates in α^(1/2) and
// μ^(1/3), and its stated error, measured at the centres of those cells, is under half the linear
// grid's of the same size (GGX bends most at small α and at grazing μ: 0.020 against 0.047). The
// C++ lookup at a node gives the node's value; the GLSL compiles.
TEST_F(Cli, LutAxesSpacedInPowersLookUpInThem) {
  const auto stated = [](const std::string& code) {
    const std::size_t at = code.find("at the cells' centres: ");
    return std::stod(code.substr(at + 23));
  };
  const std::string spaced = ok({"lut", "--model", "ggx", "--sweep", "alpha=0.01:1@12:pow2", "--mu", "0.01:1@12:pow3",
                                 "--format", "cpp", "-q"}).out;
  const std::string linear = ok({"lut", "--model", "ggx", "--sweep", "alpha=0.01:1@12", "--mu", "0.01:1@12",
                                 "--format", "cpp", "-q"}).out;
  EXPECT_THAT(spaced, HasSubstr("alpha = (0.1 + 0.0818181818 i)^2, i < 12"));
  EXPECT_THAT(spaced, HasSubstr("locate(std::pow(p, 0.5f), kPFirst"));
  EXPECT_LT(stated(spaced), stated(linear) / 2) << "spaced " << stated(spaced) << ", linear " << stated(linear);
  const fs::path header = work() / "lut.h", program = work() / "lut.cpp", binary = work() / "lut";
  std::ofstream(header) << spaced;
  std::ofstream(program) << "#include \"lut.h\"\n#include <cstdio>\n"
                            "int main() { std::printf(\"%.6f\", specula_lut::energy(1.0f, 1.0f)); }\n";
  ASSERT_EQ(std::system(fmt::format("c++ -std=c++20 -o '{}' '{}'", binary.string(), program.string()).c_str()), 0);
  const std::string node = ok({"lut", "--model", "ggx", "-p", "alpha=1", "--mu", "1", "--round", "6", "-q"}).out;
  // α = 1, μ = 1: a node, where the lookup gives the table's float.
  EXPECT_NEAR(std::stod(run_command(binary.string()).log), std::stod(node.substr(node.rfind(',') + 1)), 2e-6);
  const std::string glsl = ok({"lut", "--model", "ggx", "--sweep", "alpha=0.01:1@4:pow2", "--mu", "0.01:1@4:pow3",
                               "--format", "glsl", "-q"}).out;
  EXPECT_TRUE(validate_glsl("#version 330\n" + glsl + "out vec4 c;\nvoid main() { c = vec4(specula_lut_energy(0.5, 0.3)); }\n",
                            "frag").ok);
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--mu", "0.1,0.2,0.5", "--format", "cpp"}).err, HasSubstr("a:b@count:powK"));
}

// A second --sweep is a third axis, here the exact dielectric's F0 of cook-torrance-1982 (E is not
// linear in it): the CSV's rows are the one-table runs at each q, q-major; npy has a first axis of
// q; the code's trilinear lookup compiles (GLSL, HLSL; the control: called without q, it does not),
// gives the cubature at a node and stays within its stated error at the centre of a cell. About
// 6 s under the sanitizers (Cook-Torrance is the costliest albedo; two compiles).
TEST_F(Cli, LutASecondSweepIsAThirdAxis) {
  const std::vector<std::string> base{"lut", "--model", "cook-torrance-1982", "--sweep", "m=0.2:0.5@3", "--mu", "0.5:1@3", "-q"};
  const auto with = [&](const std::vector<std::string>& extra) { return joined(base, extra); };
  const auto cube = lines_of(ok(with({"--sweep", "f0=0.04:0.5@3", "--round", "12"})).out);
  ASSERT_EQ(cube.size(), 2u + 27);
  EXPECT_EQ(cube[1], "f0,m,mu,E");
  for (const auto& [k, f0] : {std::pair{0, "0.04"}, {2, "0.5"}}) {
    const auto table = lines_of(ok(with({"-p", std::string("f0=") + f0, "--round", "12"})).out);
    for (std::size_t r = 0; r < 9; ++r) EXPECT_EQ(cube[2 + 9 * k + r], std::string(f0) + "," + table[2 + r]) << r;
  }
  const fs::path npy = work() / "e.npy";
  ok(with({"--sweep", "f0=0.04:0.5@3", "--format", "npy", "-o", npy.string()}));
  EXPECT_THAT(bytes_of(npy), HasSubstr("'shape': (3, 3, 3), }"));
  const std::string glsl = ok(with({"--sweep", "f0=0.04:0.5@3", "--average", "--format", "glsl"})).out;
  EXPECT_THAT(glsl, HasSubstr("Trilinear interpolation error"));
  const auto compiles = [&](const std::string& call) {
    return validate_glsl("#version 330\n" + glsl + "out vec4 c;\nvoid main() { c = vec4(" + call + "); }\n", "frag").ok;
  };
  EXPECT_TRUE(compiles("specula_lut_energy(0.6, 0.3, 0.1) + specula_lut_energy_average(0.3, 0.1)"));
  EXPECT_FALSE(compiles("specula_lut_energy(0.6, 0.3)"));  // the control
  const std::string hlsl = ok(with({"--sweep", "f0=0.04:0.5@3", "--format", "hlsl"})).out;
  const fs::path hlsl_file = work() / "lut.hlsl";
  std::ofstream(hlsl_file) << hlsl << "float4 main(float4 pos : SV_Position) : SV_Target { return specula_lut_energy(0.6, 0.3, 0.1); }\n";
  EXPECT_TRUE(run_command(fmt::format("'{}' -D -V -e main -S frag '{}' -o '{}'", SPECULA_GLSLANG, hlsl_file.string(),
                                      (work() / "lut.spv").string())).ok);
  const std::string cpp = ok(with({"--sweep", "f0=0.04:0.5@3", "--format", "cpp"})).out;
  const std::size_t at = cpp.find("at the cells' centres: ");
  const double stated = std::stod(cpp.substr(at + 23));
  const fs::path header = work() / "lut.h", program = work() / "lut.cpp", binary = work() / "lut";
  std::ofstream(header) << cpp;
  std::ofstream(program) << "#include \"lut.h\"\n#include <cstdio>\nint main() { std::printf(\"%.9f %.9f\", "
                            "specula_lut::energy(0.75f, 0.35f, 0.27f), specula_lut::energy(0.625f, 0.275f, 0.155f)); }\n";
  ASSERT_EQ(std::system(fmt::format("c++ -std=c++20 -o '{}' '{}'", binary.string(), program.string()).c_str()), 0);
  std::istringstream printed(run_command(binary.string()).log);
  double node = 0, centre = 0;
  printed >> node >> centre;
  const auto albedo = [&](const char* m, const char* f0, const char* mu) {
    const std::string out = ok({"lut", "--model", "cook-torrance-1982", "-p", std::string("m=") + m, "-p",
                                std::string("f0=") + f0, "--mu", mu, "-q"}).out;
    return std::stod(out.substr(out.rfind(',') + 1));
  };
  EXPECT_NEAR(node, albedo("0.35", "0.27", "0.75"), 1e-6);
  EXPECT_NEAR(centre, albedo("0.275", "0.155", "0.625"), stated + 1e-6);
  EXPECT_THAT(bad(with({"--sweep", "f0=0.1,0.2", "--sweep", "rho=1"})).err, HasSubstr("at most two"));
  EXPECT_THAT(bad(with({"--sweep", "m=0.1,0.2"})).err, HasSubstr("given twice"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--schlick-split", "--sweep", "alpha=0.1", "--sweep", "f0=0.1"}).err,
              HasSubstr("takes one --sweep"));
  EXPECT_THAT(bad({"lut", "--model", "ggx", "--sweep", "alpha=0.1:1@100", "--sweep", "f0=0:1@10", "--mu", "0.1:1@100"}).err,
              HasSubstr("10 tables of 100 x 100 cells is more than 65536"));
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
