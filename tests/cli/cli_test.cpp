// The `specula` command line, run as a program: output text and numbers, exit codes, one-line
// errors, --help, and files written with --out.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "specula/models/model.h"
#include "text_support.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using specula::testing::cells_of;
using specula::testing::lines_of;
using specula::testing::read_file;
using ::testing::IsEmpty;

constexpr double kPi = std::numbers::pi;
// Independent mpmath values (MATH.md §4).
constexpr double kCoef1 = 0.48274947790781993;
constexpr double kCoef1000 = 197.49861008019518;




double number(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  EXPECT_TRUE(!text.empty() && *end == '\0') << "not a number: '" << text << "'";
  return value;
}

struct Csv {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
};

Csv parse_csv(const std::string& text) {
  Csv csv;
  const auto lines = lines_of(text);
  if (lines.empty()) return csv;
  csv.columns = cells_of(lines[0]);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    std::vector<double> row;
    for (const auto& cell : cells_of(lines[i])) row.push_back(number(cell));
    EXPECT_EQ(row.size(), csv.columns.size()) << "line " << i << ": " << lines[i];
    csv.rows.push_back(std::move(row));
  }
  return csv;
}

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

struct Result {
  int code = -1;
  std::string out;
  std::string err;
};

std::ostream& operator<<(std::ostream& os, const Result& r) {
  return os << "exit " << r.code << "\n--- stdout:\n" << r.out << "--- stderr:\n" << r.err;
}

// A fresh directory per test, removed afterwards; also holds the captured stdout/stderr.
class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ = fs::temp_directory_path() /
           fmt::format("specula-cli-test-{}-{}-{}", ::getpid(), counter++,
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "work");
    fs::create_directories(dir_ / "capture");
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

  /// An empty directory for the command's files.
  fs::path work() const { return dir_ / "work"; }

  /// Runs `specula args…` (no shell), capturing stdout, stderr and the exit code.
  Result run(const std::vector<std::string>& args) {
    const fs::path out = dir_ / "capture" / "stdout";
    const fs::path err = dir_ / "capture" / "stderr";
    std::vector<std::string> argv_strings{SPECULA_CLI};
    argv_strings.insert(argv_strings.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : argv_strings) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = 0;
    const int spawned = posix_spawn(&pid, SPECULA_CLI, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    Result r;
    if (spawned != 0) {
      ADD_FAILURE() << "cannot run " << SPECULA_CLI << ": " << std::strerror(spawned);
      return r;
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = read_file(out);
    r.err = read_file(err);
    return r;
  }

  /// Runs a command that must succeed with nothing on stderr.
  Result ok(const std::vector<std::string>& args) {
    Result r = run(args);
    EXPECT_EQ(r.code, 0) << fmt::format("specula {}\n", fmt::join(args, " ")) << r;
    EXPECT_THAT(r.err, IsEmpty()) << fmt::format("specula {}", fmt::join(args, " "));
    return r;
  }

  /// Runs a command that must fail as bad input: exit 2, one line on stderr, nothing on stdout.
  Result bad(const std::vector<std::string>& args) {
    Result r = run(args);
    const std::string what = fmt::format("specula {}\n", fmt::join(args, " "));
    EXPECT_EQ(r.code, 2) << what << r;
    EXPECT_THAT(r.out, IsEmpty()) << what << r;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << what << r;
    EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << what << r;
    return r;
  }

 private:
  fs::path dir_;
};

// ---- normalize ------------------------------------------------------------------------------

TEST_F(Cli, NormalizePrintsThePapersTable) {
  const Result r = ok({"normalize", "--model", "log", "--n", "1:7", "--round", "3"});
  EXPECT_EQ(r.out,
            "n,coef\n1,0.483\n2,0.665\n3,0.855\n4,1.048\n5,1.243\n6,1.438\n7,1.634\n");
}

TEST_F(Cli, NormalizeBothMethodsAgreeWithMpmath) {
  const Result r = ok({"normalize", "--model", "log", "--n", "1,1000", "--method", "both"});
  const Csv csv = parse_csv(r.out);
  EXPECT_THAT(csv.columns, ElementsAre("n", "coef", "coef_quadrature", "rel_diff"));
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0][0], 1.0);
  EXPECT_EQ(csv.rows[1][0], 1000.0);
  EXPECT_NEAR(csv.rows[0][1], kCoef1, 1e-15 * kCoef1);
  EXPECT_NEAR(csv.rows[1][1], kCoef1000, 1e-15 * kCoef1000);
  for (const auto& row : csv.rows) {
    EXPECT_LT(std::abs(row[3]), 1e-12);
    EXPECT_NEAR(row[2], row[1], 1e-12 * row[1]);
    EXPECT_DOUBLE_EQ(row[3], (row[2] - row[1]) / row[1]);
  }
}

TEST_F(Cli, NormalizeCompareWithThePapersFit) {
  const Result r = ok({"normalize", "--model", "log", "--n", "1000", "--compare", "log-paper"});
  const Csv csv = parse_csv(r.out);
  EXPECT_THAT(csv.columns, ElementsAre("n", "coef", "coef_compare", "delta"));
  ASSERT_EQ(csv.rows.size(), 1u);
  const double fit = 0.197 * (1000 + 1.24) + 0.068 / (0.64 + 1000);
  const double expected = fit / kCoef1000 - 1;  // MATH.md §4: ≈ −1.29e-3
  EXPECT_NEAR(expected, -1.29e-3, 5e-6);
  EXPECT_NEAR(csv.rows[0][2], fit, 1e-13 * fit);
  EXPECT_NEAR(csv.rows[0][3], expected, 2e-5);
  EXPECT_NEAR(csv.rows[0][3], expected, 1e-12);  // in fact to round-off
}

TEST_F(Cli, NormalizePhongInNhFormIsBlinnPhongsExactCoefficient) {
  for (const double n : {1.0, 20.0, 1000.0}) {
    const Result r = ok({"normalize", "--model", "phong", "--form", "nh", "--n", fmt::format("{}", n)});
    const Csv csv = parse_csv(r.out);
    ASSERT_EQ(csv.rows.size(), 1u);
    const double expected = (n + 2) * (n + 4) / (8 * kPi * (std::pow(2.0, -n / 2) + n));
    EXPECT_NEAR(csv.rows[0][1], expected, 1e-14 * expected) << "n = " << n;
  }
}

TEST_F(Cli, NormalizeExactWithoutClosedFormFails) {
  const Result r = bad({"normalize", "--model", "gauss", "--n", "20", "--method", "exact"});
  EXPECT_THAT(r.err, HasSubstr("quadrature"));
  // …and quadrature works.
  const Csv csv = parse_csv(ok({"normalize", "--model", "gauss", "--n", "20", "--method", "quadrature"}).out);
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_TRUE(std::isfinite(csv.rows[0][1]) && csv.rows[0][1] > 0);
}

TEST_F(Cli, NormalizeJsonHasTheSameNumbersAsCsv) {
  const std::vector<std::string> args{"normalize", "--model", "log", "--n", "1:3,1000", "--method", "both"};
  for (const std::vector<std::string>& extra : {std::vector<std::string>{}, {"--round", "4"}}) {
    std::vector<std::string> csv_args = args, json_args = args;
    csv_args.insert(csv_args.end(), extra.begin(), extra.end());
    json_args.insert(json_args.end(), extra.begin(), extra.end());
    json_args.insert(json_args.end(), {"--format", "json"});
    const Csv csv = parse_csv(ok(csv_args).out);
    const Result r = ok(json_args);
    nlohmann::json j;
    ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r;
    EXPECT_EQ(j["model"], "log");
    ASSERT_TRUE(j["columns"].is_array());
    EXPECT_EQ(j["columns"].get<std::vector<std::string>>(), csv.columns);
    ASSERT_TRUE(j["rows"].is_array());
    ASSERT_EQ(j["rows"].size(), csv.rows.size());
    for (std::size_t i = 0; i < csv.rows.size(); ++i)
      for (std::size_t c = 0; c < csv.columns.size(); ++c)
        EXPECT_EQ(j["rows"][i][csv.columns[c]].get<double>(), csv.rows[i][c])
            << "row " << i << " column " << csv.columns[c];
  }
}

// ---- eval -----------------------------------------------------------------------------------

TEST_F(Cli, EvalBarePhongAtCosines) {
  const Csv csv = parse_csv(ok({"eval", "--model", "phong", "-p", "n=2", "--cos", "0,0.5,1"}).out);
  EXPECT_THAT(csv.columns, ElementsAre("cos", "value"));
  ASSERT_EQ(csv.rows.size(), 3u);
  EXPECT_THAT(csv.rows[0], ElementsAre(0.0, 0.0));
  EXPECT_THAT(csv.rows[1], ElementsAre(0.5, 0.25));
  EXPECT_THAT(csv.rows[2], ElementsAre(1.0, 1.0));
}

TEST_F(Cli, EvalNormalizedPhongAndTheBareLobe) {
  const Csv normalized = parse_csv(ok({"eval", "--model", "phong-normalized", "-p", "n=2", "--cos", "1"}).out);
  ASSERT_EQ(normalized.rows.size(), 1u);
  EXPECT_NEAR(normalized.rows[0][1], 4 / (2 * kPi), 1e-15);

  const Csv lobe =
      parse_csv(ok({"eval", "--model", "phong-normalized", "-p", "n=2", "--cos", "1,0.5", "--lobe"}).out);
  ASSERT_EQ(lobe.rows.size(), 2u);
  EXPECT_EQ(lobe.rows[0][1], 1.0);
  EXPECT_EQ(lobe.rows[1][1], 0.25);
}

TEST_F(Cli, EvalLogAtACountedRange) {
  const Csv csv = parse_csv(ok({"eval", "--model", "log", "-p", "n=20", "--cos", "0.9:1@3"}).out);
  ASSERT_EQ(csv.rows.size(), 3u);
  EXPECT_EQ(csv.rows[0][0], 0.9);
  EXPECT_EQ(csv.rows[1][0], 0.95);
  EXPECT_EQ(csv.rows[2][0], 1.0);
  EXPECT_EQ(csv.rows[2][1], 1.0);  // F(1) = 1, bare lobe
}

TEST_F(Cli, EvalFullBrdfAtCosinesFails) {
  const Result r = bad({"eval", "--model", "ggx", "--cos", "0.5"});
  EXPECT_THAT(r.err, HasSubstr("--theta-i"));
}

TEST_F(Cli, EvalLambertAtDirections) {
  const Csv csv = parse_csv(ok({"eval", "--model", "lambert", "--theta-i", "30", "--theta-o", "0,45"}).out);
  EXPECT_THAT(csv.columns, ElementsAre("theta_o_deg", "value"));
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0][0], 0.0);
  EXPECT_EQ(csv.rows[1][0], 45.0);
  for (const auto& row : csv.rows) EXPECT_NEAR(row[1], 1 / kPi, 1e-15);
}

TEST_F(Cli, EvalGgxAtDirections) {
  const Csv csv = parse_csv(
      ok({"eval", "--model", "ggx", "--theta-i", "30", "--theta-o", "30", "--phi-o", "180"}).out);
  ASSERT_EQ(csv.rows.size(), 1u);
  EXPECT_TRUE(std::isfinite(csv.rows[0][1]));
  EXPECT_GT(csv.rows[0][1], 0);
}

// ---- models ---------------------------------------------------------------------------------

TEST_F(Cli, ModelsListsEveryId) {
  const Result r = ok({"models"});
  for (const char* id : {"phong", "log-normalized", "log-paper", "ggx", "ward-gmd"})
    EXPECT_THAT(r.out, HasSubstr(id));
  // Every model of the library, each on a line of its own that starts with its id.
  std::set<std::string> first_words;
  for (const auto& line : lines_of(r.out)) first_words.insert(line.substr(0, line.find(' ')));
  for (const auto& m : specula::models()) EXPECT_TRUE(first_words.contains(std::string(m.id))) << m.id;
}

TEST_F(Cli, ModelsJson) {
  const Result r = ok({"models", "--json"});
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r;
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), specula::models().size());
  std::set<std::string> ids;
  for (const auto& entry : j) {
    ASSERT_TRUE(entry.contains("id") && entry["id"].is_string()) << entry.dump();
    const std::string id = entry["id"];
    ids.insert(id);
    ASSERT_TRUE(entry.contains("kind")) << id;
    EXPECT_TRUE(entry["kind"] == "lobe" || entry["kind"] == "brdf") << id;
    ASSERT_TRUE(entry.contains("params") && entry["params"].is_array()) << id;
    for (const auto& p : entry["params"]) {
      EXPECT_TRUE(p.contains("name") && p["name"].is_string()) << id;
      for (const char* key : {"default", "min", "max"})
        EXPECT_TRUE(p.contains(key) && p[key].is_number()) << id << " " << key;
      if (p["default"].is_number() && p["min"].is_number() && p["max"].is_number()) {
        EXPECT_LE(p["min"].get<double>(), p["default"].get<double>()) << id;
        EXPECT_LE(p["default"].get<double>(), p["max"].get<double>()) << id;
      }
    }
    if (entry["kind"] == "lobe") {
      ASSERT_TRUE(entry.contains("form")) << id;
      EXPECT_TRUE(entry["form"] == "rv" || entry["form"] == "nh") << id;
      EXPECT_TRUE(entry.contains("normalization") && entry["normalization"].is_string()) << id;
    }
  }
  for (const char* id : {"phong", "log-normalized", "log-paper", "ggx", "ward-gmd"})
    EXPECT_TRUE(ids.contains(id)) << id;
  EXPECT_EQ(ids.size(), j.size());  // no duplicates
}

// ---- bad input ------------------------------------------------------------------------------

TEST_F(Cli, UnknownModel) {
  EXPECT_THAT(bad({"normalize", "--model", "nope", "--n", "1"}).err, HasSubstr("nope"));
  EXPECT_THAT(bad({"eval", "--model", "nope", "--cos", "1"}).err, HasSubstr("nope"));
  bad({"normalize", "--model", "log", "--n", "1", "--compare", "nope"});
}

TEST_F(Cli, UnknownParameter) {
  EXPECT_THAT(bad({"eval", "--model", "phong", "-p", "q=1", "--cos", "1"}).err, HasSubstr("q"));
  bad({"normalize", "--model", "log", "-p", "q=1", "--n", "1"});
}

TEST_F(Cli, NonPositiveN) {
  bad({"normalize", "--model", "log", "--n", "0"});
  bad({"normalize", "--model", "log", "--n", "-1"});
  bad({"normalize", "--model", "log", "--n", "1,2,0"});
  bad({"eval", "--model", "phong", "-p", "n=-3", "--cos", "1"});
}

TEST_F(Cli, NaN) {
  EXPECT_THAT(bad({"normalize", "--model", "log", "--n", "nan"}).err, HasSubstr("nan"));
  EXPECT_THAT(bad({"eval", "--model", "phong", "-p", "n=nan", "--cos", "1"}).err, HasSubstr("nan"));
  bad({"eval", "--model", "phong", "--cos", "nan"});
}

TEST_F(Cli, MalformedRange) {
  EXPECT_THAT(bad({"normalize", "--model", "log", "--n", "1:"}).err, HasSubstr("1:"));
  EXPECT_THAT(bad({"normalize", "--model", "log", "--n", "5:1"}).err, HasSubstr("5:1"));
}

TEST_F(Cli, MalformedParam) {
  EXPECT_THAT(bad({"eval", "--model", "phong", "-p", "n", "--cos", "1"}).err, HasSubstr("n"));
  bad({"eval", "--model", "phong", "-p", "=3", "--cos", "1"});
  bad({"eval", "--model", "phong", "-p", "n=3x", "--cos", "1"});
}

TEST_F(Cli, BadForm) {
  EXPECT_THAT(bad({"normalize", "--model", "phong", "--form", "xy", "--n", "1"}).err, HasSubstr("xy"));
  bad({"eval", "--model", "phong", "--form", "xy", "--cos", "1"});
}

TEST_F(Cli, BadFormatAndRound) {
  bad({"normalize", "--model", "log", "--n", "1", "--format", "xml"});
  bad({"normalize", "--model", "log", "--n", "1", "--round", "-1"});
  bad({"normalize", "--model", "log", "--n", "1", "--round", "x"});
  bad({"normalize", "--model", "log", "--n", "1", "--method", "bogus"});
}

TEST_F(Cli, OutOfRangeCosAndAngles) {
  EXPECT_THAT(bad({"eval", "--model", "phong", "--cos", "1.5"}).err, HasSubstr("1.5"));
  EXPECT_THAT(bad({"eval", "--model", "lambert", "--theta-i", "95", "--theta-o", "0"}).err,
              HasSubstr("95"));
  bad({"eval", "--model", "lambert", "--theta-i", "30", "--theta-o", "0,95"});
  bad({"eval", "--model", "ggx", "--theta-i", "30", "--theta-o", "0", "--phi-o", "400"});
}

TEST_F(Cli, NaNAngles) {
  EXPECT_THAT(bad({"eval", "--model", "lambert", "--theta-i", "nan", "--theta-o", "0"}).err,
              HasSubstr("--theta-i"));
  EXPECT_THAT(bad({"eval", "--model", "ggx", "--theta-i", "30", "--theta-o", "0", "--phi-o", "nan"}).err,
              HasSubstr("--phi-o"));
  bad({"eval", "--model", "lambert", "--theta-i", "30", "--theta-o", "nan"});
}

TEST_F(Cli, ConflictingOrIncompleteEvalOptions) {
  bad({"eval", "--model", "phong", "--cos", "1", "--theta-i", "30", "--theta-o", "0"});
  bad({"eval", "--model", "ggx", "--theta-i", "30"});
  bad({"eval", "--model", "ggx", "--form", "nh", "--theta-i", "30", "--theta-o", "0"});
  bad({"normalize", "--model", "log", "--n", "1e10"});  // above the parameter's range
}

TEST_F(Cli, MissingModelSubcommandOrArguments) {
  EXPECT_THAT(bad({"normalize", "--n", "1"}).err, HasSubstr("--model"));
  bad({"eval", "--cos", "1"});
  bad({"frobnicate"});
  bad({});
  bad({"eval", "--model", "phong"});  // neither --cos nor directions
}

TEST_F(Cli, NormalizeRejectsNAsAParam) {
  bad({"normalize", "--model", "log", "--param", "n=5", "--n", "5"});
  bad({"normalize", "--model", "log", "-p", "n=5"});
}

TEST_F(Cli, NormalizeRejectsAFullBrdf) { bad({"normalize", "--model", "ggx", "--n", "1"}); }

// ---- help -----------------------------------------------------------------------------------

TEST_F(Cli, HelpEverywhereHasAnExample) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--help"}, {"models", "--help"}, {"eval", "--help"},
        {"normalize", "--help"}, {"report", "--help"}}) {
    const Result r = run(args);
    const std::string what = fmt::format("specula {}", fmt::join(args, " "));
    EXPECT_EQ(r.code, 0) << what << "\n" << r;
    EXPECT_THAT(r.out, HasSubstr("Example")) << what;
  }
}

// ---- files ----------------------------------------------------------------------------------

TEST_F(Cli, OutWritesTheFileAndNothingElse) {
  const fs::path file = work() / "x.csv";
  const Result r = ok({"normalize", "--model", "log", "--n", "1:7", "--round", "3", "--out", file.string()});
  EXPECT_THAT(r.out, IsEmpty());
  EXPECT_EQ(read_file(file), "n,coef\n1,0.483\n2,0.665\n3,0.855\n4,1.048\n5,1.243\n6,1.438\n7,1.634\n");
  EXPECT_THAT(listing(work()), ElementsAre("x.csv"));

  // Overwrites atomically, still one file.
  ok({"normalize", "--model", "log", "--n", "1", "--format", "json", "--out", file.string()});
  EXPECT_TRUE(nlohmann::json::accept(read_file(file)));
  EXPECT_THAT(listing(work()), ElementsAre("x.csv"));
}

TEST_F(Cli, FailingCommandNeverCreatesItsOutFile) {
  const fs::path file = work() / "x.csv";
  bad({"normalize", "--model", "nope", "--n", "1:7", "--out", file.string()});
  // A bad value late in the list: the rows before it must not reach the file either.
  bad({"normalize", "--model", "log", "--n", "1:7,0", "--out", file.string()});
  bad({"eval", "--model", "phong", "--cos", "0,0.5,2", "--out", file.string()});
  EXPECT_THAT(listing(work()), IsEmpty());

  // An existing file is left as it was.
  ok({"normalize", "--model", "log", "--n", "1", "--out", file.string()});
  const std::string before = read_file(file);
  bad({"normalize", "--model", "log", "--n", "1,nan", "--out", file.string()});
  EXPECT_EQ(read_file(file), before);
  EXPECT_THAT(listing(work()), ElementsAre("x.csv"));
}

TEST_F(Cli, OutIntoANonexistentDirectory) {
  const fs::path file = work() / "missing" / "x.csv";
  const Result r = bad({"normalize", "--model", "log", "--n", "1", "--out", file.string()});
  EXPECT_THAT(r.err, HasSubstr(file.string()));
  EXPECT_THAT(listing(work()), IsEmpty());
}

TEST_F(Cli, OutOntoADirectory) {
  const Result r = bad({"models", "--out", work().string()});
  EXPECT_THAT(r.err, HasSubstr(work().string()));
  EXPECT_TRUE(fs::is_directory(work()));
  EXPECT_THAT(listing(work()), IsEmpty());
  EXPECT_THAT(listing(work().parent_path()), ::testing::UnorderedElementsAre("work", "capture"));
}

TEST_F(Cli, ReportWritesIndexAndFig5) {
  const fs::path out = work() / "report";
  const Result r = run({"report", "--out", out.string()});
  ASSERT_EQ(r.code, 0) << r;
  EXPECT_THAT(r.out, IsEmpty());
  ASSERT_TRUE(fs::exists(out / "index.html"));
  ASSERT_TRUE(fs::exists(out / "fig5-normalization.csv"));
  EXPECT_THAT(read_file(out / "index.html"), HasSubstr("<html"));
  const std::string csv = read_file(out / "fig5-normalization.csv");
  EXPECT_EQ(lines_of(csv).size(), 51u);
  const Csv table = parse_csv(csv);
  ASSERT_EQ(table.rows.size(), 50u);
  EXPECT_EQ(table.rows.front()[0], 1.0);
  EXPECT_EQ(table.rows.back()[0], 1000.0);
  EXPECT_NEAR(table.rows.front()[1], kCoef1, 1e-15 * kCoef1);
  EXPECT_NEAR(table.rows.back()[1], kCoef1000, 1e-15 * kCoef1000);
  for (const auto& name : listing(out)) EXPECT_EQ(name.find(".tmp"), std::string::npos) << name;
}

TEST_F(Cli, ReportIntoAFileFails) {
  const fs::path file = work() / "afile";
  std::ofstream(file) << "x";
  const Result r = bad({"report", "--out", file.string()});
  EXPECT_THAT(r.err, HasSubstr(file.string()));
  EXPECT_THAT(listing(work()), ElementsAre("afile"));
}

}  // namespace
