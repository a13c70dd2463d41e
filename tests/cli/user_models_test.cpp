// User-defined models through the CLI: --models FILE before or after the command, inline models
// wherever a model id goes, the built-in's numbers from a user's copy, and bad model files as one
// line naming FILE:LINE (and the column), exit 2, no output.
#include <fstream>

#include "cli_fixture.h"

namespace specula::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

const std::string kCopies = SPECULA_SOURCE_DIR "/examples/models/builtin-copies.toml";

double last_number(const std::string& csv) {
  const auto comma = csv.find_last_of(',');
  return std::stod(csv.substr(comma + 1));
}

TEST_F(Cli, ModelsFromAFileAreListedAfterTheBuiltIns) {
  const Result r = ok({"--models", kCopies, "models"});
  EXPECT_THAT(r.out, HasSubstr("my-log "));
  EXPECT_LT(r.out.find("ggx "), r.out.find("my-phong "));
  EXPECT_THAT(ok({"models", "--models", kCopies, "--json"}).out, HasSubstr("\"origin\": \"" + kCopies + ":87\""));
}

TEST_F(Cli, AUsersCopyGivesTheBuiltInsNumbers) {
  const auto normalize = [&](const std::string& model) {
    return last_number(ok({"normalize", "--models", kCopies, "--model", model, "--n", "1000"}).out);
  };
  EXPECT_NEAR(normalize("my-log") / normalize("log"), 1, 1e-12);
  const auto albedo = [&](const std::string& model) {
    return last_number(ok({"albedo", "--models", kCopies, "--model", model, "--theta", "60"}).out);
  };
  EXPECT_NEAR(albedo("my-ggx"), albedo("ggx"), 1e-9);
  EXPECT_NEAR(albedo("my-log"), albedo("log-normalized"), 1e-9);
}

TEST_F(Cli, AnInlineLobeWorksWhereAModelIdDoes) {
  EXPECT_EQ(ok({"eval", "--model", "lobe: c^n", "-p", "n=20", "--cos", "0.5"}).out, "cos,value\n0.5,9.5367431640625e-07\n");
  // The example: k = 1/(2π(1/(5a) − 1/(30a²))), a = n/4 (closed form), at n = 10.
  const double k = last_number(ok({"normalize", "--model", "lobe: max(0, 1 - n*(1-c)/4)^4", "--n", "10"}).out);
  EXPECT_NEAR(k, 1 / (2 * 3.14159265358979323846 * (1 / 12.5 - 1 / 187.5)), 1e-12 * k);
  const Result brdf = ok({"check", "--model", "brdf: rho/pi", "-p", "rho=0.5"});
  EXPECT_THAT(brdf.out, HasSubstr("energy conservation         holds"));
}

TEST_F(Cli, CheckReportsAFormulaThatBreaksTheRulesAsAFailureNotAnInputError) {
  const Result r = run({"check", "--model", "lobe: c - 0.5"});
  EXPECT_EQ(r.code, 1) << r;
  EXPECT_THAT(r.out, HasSubstr("non-negativity"));
}

TEST_F(Cli, BadModelFilesAreOneLineNamingFileLineAndColumn) {
  const fs::path file = work() / "m.toml";
  const auto write = [&](const std::string& text) { std::ofstream(file, std::ios::binary) << text; };
  write("[[model]]\nid = \"x\"\nname = \"x\"\nkind = \"lobe\"\nform = \"rv\"\nlobe = \"c^*n\"\nnormalization = \"none\"\n");
  EXPECT_EQ(bad({"--models", file.string(), "models"}).err,
            "specula: error: " + file.string() + ":6: column 11: lobe: expected a number, a variable, a function call or '(' but found '*'\n");
  write("[[model]]\nid = \"phong\"\nname = \"x\"\nkind = \"brdf\"\nbrdf = \"1\"\n");
  EXPECT_THAT(bad({"models", "--models", file.string()}).err, HasSubstr(":1: model id 'phong' is already taken"));
  write("[[model]]\nid = \"y\"\nname = \"y\"\nkind = \"brdf\"\nbrdf = \"1\"\ncolour = 3\n");
  EXPECT_THAT(bad({"eval", "--models", file.string(), "--model", "y", "--theta-i", "0", "--theta-o", "0"}).err,
              HasSubstr(":6: unknown key 'colour' in a model"));
  EXPECT_THAT(bad({"models", "--models", (work() / "missing.toml").string()}).err, HasSubstr("missing.toml"));
  EXPECT_THAT(bad({"eval", "--model", "lobe: c^", "--cos", "0.5"}).err, StartsWith("specula: error: --model: column 9: "));
}

}  // namespace
}  // namespace specula::testing
