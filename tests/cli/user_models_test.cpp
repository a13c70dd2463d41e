// User-defined models through the CLI: --models FILE before or after the command, inline models
// wherever a model id goes, the built-in's numbers from a user's copy, and bad model files as one
// line naming FILE:LINE (and the column), exit 2, no output.
#include <filesystem>
#include <fstream>

#include "cli_fixture.h"
#include "text_support.h"

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

// compare took an inline model's catalogue entry, which does not exist: a segmentation fault.
TEST_F(Cli, CompareTakesInlineModelsAsPanelsAndAsReference) {
  const std::string png = (work() / "c.png").string();
  ok({"compare", "--models", "lobe: c^n,phong", "-p", "n=20", "--size", "16x16", "-o", png, "-q"});
  EXPECT_TRUE(std::filesystem::exists(png));
  ok({"compare", "--models", "phong", "--diff", "lobe: c^n", "-p", "n=20", "--size", "16x16", "-o", png, "-q"});
  EXPECT_THAT(bad({"compare", "--models", "lobe: c^n", "-p", "m=2", "--size", "16x16", "-o", png}).err,
              HasSubstr("no model in this comparison has a parameter 'm'"));
}

TEST_F(Cli, ErrorTakesAUsersLobeAsModelAndAsReference) {
  const auto error = [&](const std::string& model, const std::string& reference) {
    return ok({"--models", kCopies, "error", "--model", model, "--reference", reference, "--n", "10,1000"}).out;
  };
  const auto columns = [](const std::string& csv) {
    std::vector<double> values;
    for (const auto& line : lines_of(csv))
      if (line.front() != 'n')
        for (const auto& cell : cells_of(line)) values.push_back(std::stod(cell));
    return values;
  };
  const auto builtin = columns(error("log", "phong"));
  ASSERT_EQ(builtin.size(), 10u);
  for (const auto& [model, reference] : {std::pair{"my-log", "phong"}, {"log", "my-phong"}, {"my-log", "my-phong"}}) {
    const auto user = columns(error(model, reference));
    ASSERT_EQ(user.size(), builtin.size());
    for (std::size_t i = 0; i < user.size(); ++i)  // columns n, max_abs, argmax_abs_deg, max_rel_…
      EXPECT_NEAR(user[i], builtin[i], i % 5 == 2 ? 1e-4 : 1e-9) << model << " " << reference << " " << i;
  }
  EXPECT_GT(std::abs(columns(error("my-schlick", "phong"))[1] - builtin[1]), 1e-3);  // control: another lobe
}

TEST_F(Cli, FitTakesAUsersLobeAndFitsItsNormalization) {
  // An exhaustive search (every formula up to size 3, no genetic generations) is deterministic:
  // the copy's k(n) gives the built-in's front, error for error.
  const auto front = [&](const std::string& model) {
    return ok({"--models", kCopies, "fit", "--model", model, "--n", "1:1000@30:log", "--max-size", "3",
               "--enumerate-size", "3", "--generations", "0", "--format", "json", "--threads", "1", "--quiet"}).out;
  };
  const auto train_errors = [](const std::string& json) {
    std::vector<double> errors;
    for (auto at = json.find("\"train_error\": "); at != std::string::npos; at = json.find("\"train_error\": ", at + 1))
      errors.push_back(std::stod(json.substr(at + 15)));
    return errors;
  };
  const std::string mine = front("my-log"), builtin = front("log");
  EXPECT_THAT(mine, HasSubstr("\"data\": \"my-log normalization\""));
  const auto a = train_errors(mine), b = train_errors(builtin), other = train_errors(front("my-schlick"));
  ASSERT_FALSE(a.empty());
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-9 * (1 + b[i])) << i;
  EXPECT_GT(std::abs(other.back() - b.back()), 1e-6 * (1 + b.back()));  // control: another lobe
  EXPECT_THAT(bad({"fit", "--model", "log", "--data", "x.csv", "--target", "coef"}).err, HasSubstr("one of them"));
  EXPECT_THAT(bad({"fit", "--model", "ggx"}).err, HasSubstr("full BRDF"));
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
