// The `specula` command line, run as a program: output text and numbers, exit codes, one-line
// errors, --help, and files written with --out.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
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

#include "specula/expr/expr.h"
#include "specula/catalogue/catalogue.h"
#include "cli_fixture.h"
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
using ::testing::MatchesRegex;
using specula::testing::Cli;
using specula::testing::Result;
using specula::testing::listing;

constexpr double kPi = std::numbers::pi;
// Independent mpmath values (docs/math.md §4).
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

double deg_of(double radians) { return radians * 180 / kPi; }

/// The one value of a CSV column, by name (the table must have exactly one row).
double only(const Csv& csv, const std::string& column) {
  const auto it = std::find(csv.columns.begin(), csv.columns.end(), column);
  EXPECT_NE(it, csv.columns.end()) << "no column " << column;
  EXPECT_EQ(csv.rows.size(), 1u);
  if (it == csv.columns.end() || csv.rows.size() != 1) return std::nan("");
  return csv.rows[0][static_cast<std::size_t>(it - csv.columns.begin())];
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++count;
  return count;
}

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
  const double expected = fit / kCoef1000 - 1;  // docs/math.md §4: ≈ −1.29e-3
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
  EXPECT_THAT(r.err, HasSubstr("; use --method quadrature"));
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

TEST_F(Cli, NormalizeStrictEqualsTheExactCoefficientWhereTheAlbedoPeaksAtNormalIncidence) {
  // The log lobe's albedo is largest at θ_i = 0, so max ρ = 1 is ρ(0) = 1: the paper's k.
  const Csv csv =
      parse_csv(ok({"normalize", "--model", "log", "--n", "1,20,1000", "--condition", "strict", "--step", "10"}).out);
  EXPECT_THAT(csv.columns, ElementsAre("n", "coef"));
  const Csv exact = parse_csv(ok({"normalize", "--model", "log", "--n", "20", "--method", "exact"}).out);
  ASSERT_EQ(csv.rows.size(), 3u);
  ASSERT_EQ(exact.rows.size(), 1u);
  EXPECT_EQ(csv.rows[1][0], 20.0);
  EXPECT_NEAR(csv.rows[0][1], kCoef1, 1e-9 * kCoef1);
  EXPECT_NEAR(csv.rows[1][1], exact.rows[0][1], 1e-9 * exact.rows[0][1]);
  EXPECT_NEAR(csv.rows[2][1], kCoef1000, 1e-9 * kCoef1000);
}

TEST_F(Cli, NormalizeStrictMakesTheMaximumAlbedoOne) {
  const double strict = only(
      parse_csv(ok({"normalize", "--model", "gauss", "--n", "10", "--condition", "strict", "--step", "10"}).out),
      "coef");
  const double normal = only(parse_csv(ok({"normalize", "--model", "gauss", "--n", "10"}).out), "coef");
  ASSERT_TRUE(std::isfinite(strict) && strict > 0);
  // max ρ ≥ ρ(0), so the strict k is never above the paper's (here the two agree: ρ peaks at 0).
  EXPECT_LE(strict, normal * (1 + 1e-9));
  const Csv albedo = parse_csv(
      ok({"albedo", "--model", "gauss", "-p", "n=10", "--coef", fmt::format("{}", strict), "--theta", "0:80:10"}).out);
  ASSERT_EQ(albedo.rows.size(), 9u);
  double max = 0;
  for (const auto& row : albedo.rows) max = std::max(max, row[1]);
  EXPECT_LE(max, 1 + 1e-7);
  EXPECT_GE(max, 1 - 1e-7);
}

TEST_F(Cli, NormalizeBadCondition) {
  EXPECT_THAT(bad({"normalize", "--model", "gauss", "--n", "10", "--condition", "strict", "--method", "exact"}).err,
              HasSubstr("strict"));
  EXPECT_THAT(bad({"normalize", "--model", "gauss", "--n", "10", "--condition", "nope"}).err, HasSubstr("nope"));
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

// ---- albedo ---------------------------------------------------------------------------------

TEST_F(Cli, AlbedoOfLambertIsOne) {
  const Csv csv = parse_csv(ok({"albedo", "--model", "lambert", "--theta", "0,45,80"}).out);
  EXPECT_THAT(csv.columns, ElementsAre("theta_deg", "albedo"));
  ASSERT_EQ(csv.rows.size(), 3u);
  EXPECT_EQ(csv.rows[0][0], 0.0);
  EXPECT_EQ(csv.rows[1][0], 45.0);
  EXPECT_EQ(csv.rows[2][0], 80.0);
  for (const auto& row : csv.rows) EXPECT_NEAR(row[1], 1.0, 1e-8) << "theta " << row[0];
}

TEST_F(Cli, AlbedoOfANormalizedLobeAboveTheHorizonIsCosTheta) {
  // At θ_i = 30° the n = 20 log lobe (support ≈ 26°) stays above the horizon: ρ = k·2π·Int·cos θ_i.
  const double cubature =
      only(parse_csv(ok({"albedo", "--model", "log-normalized", "-p", "n=20", "--theta", "30"}).out), "albedo");
  EXPECT_NEAR(cubature, std::cos(30 * kPi / 180), 1e-9);

  const Csv mc = parse_csv(ok({"albedo", "--model", "log-normalized", "-p", "n=20", "--theta", "30", "--method",
                               "monte-carlo", "--samples", "20000", "--seed", "3"})
                               .out);
  EXPECT_THAT(mc.columns, ElementsAre("theta_deg", "albedo", "standard_error"));
  const double se = only(mc, "standard_error");
  EXPECT_GT(se, 0);
  EXPECT_LT(se, 0.05);
  EXPECT_NEAR(only(mc, "albedo"), cubature, 5 * se);
}

TEST_F(Cli, AlbedoJsonAndCoefOverride) {
  const Result r = ok({"albedo", "--model", "log-normalized", "-p", "n=20", "--theta", "30", "--format", "json"});
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r;
  EXPECT_EQ(j["model"], "log-normalized");
  EXPECT_EQ(j["method"], "cubature");
  EXPECT_EQ(j["columns"].get<std::vector<std::string>>(), (std::vector<std::string>{"theta_deg", "albedo"}));
  ASSERT_TRUE(j["rows"].is_array());
  ASSERT_EQ(j["rows"].size(), 1u);
  EXPECT_EQ(j["rows"][0]["theta_deg"].get<double>(), 30.0);
  const double albedo = j["rows"][0]["albedo"].get<double>();
  EXPECT_NEAR(albedo, std::cos(30 * kPi / 180), 1e-9);

  // --coef replaces k: twice the model's own k reflects twice as much.
  ASSERT_TRUE(j.contains("coef")) << r;
  const double k = number(j["coef"].is_string() ? j["coef"].get<std::string>() : j["coef"].dump());
  ASSERT_GT(k, 0);
  const Csv doubled = parse_csv(ok({"albedo", "--model", "log-normalized", "-p", "n=20", "--theta", "30", "--coef",
                                    fmt::format("{}", 2 * k)})
                                    .out);
  EXPECT_NEAR(only(doubled, "albedo"), 2 * albedo, 1e-12);
}

TEST_F(Cli, AlbedoBadInput) {
  EXPECT_THAT(bad({"albedo", "--model", "lambert", "--theta", "90"}).err, HasSubstr("90"));
  EXPECT_THAT(bad({"albedo", "--model", "lambert", "--theta", "-1"}).err, HasSubstr("-1"));
  EXPECT_THAT(bad({"albedo", "--model", "lambert", "--theta", "nan"}).err, HasSubstr("nan"));
  EXPECT_THAT(bad({"albedo", "--model", "log-normalized", "--theta", "0", "--coef", "0"}).err, HasSubstr("coef"));
  bad({"albedo", "--model", "log-normalized", "--theta", "0", "--coef", "-1"});
  EXPECT_THAT(bad({"albedo", "--model", "ggx", "--coef", "2", "--theta", "0"}).err, HasSubstr("ggx"));
  EXPECT_THAT(bad({"albedo", "--model", "lambert", "--theta", "0", "--method", "nope"}).err, HasSubstr("nope"));
  EXPECT_THAT(
      bad({"albedo", "--model", "lambert", "--theta", "0", "--method", "monte-carlo", "--samples", "0"}).err,
      HasSubstr("--samples"));
}

// ---- check ----------------------------------------------------------------------------------

TEST_F(Cli, CheckNormalizedLogHolds) {
  const Result r = ok({"check", "--model", "log-normalized", "--n", "1,20", "--step", "30", "--pairs", "500"});
  EXPECT_THAT(r.out, HasSubstr("log-normalized (n=1)"));
  EXPECT_THAT(r.out, HasSubstr("log-normalized (n=20)"));
  EXPECT_EQ(occurrences(r.out, "energy conservation"), 2u) << r;
  EXPECT_EQ(occurrences(r.out, "holds"), 6u) << r;  // 3 properties × 2 values of n
  EXPECT_EQ(occurrences(r.out, "FAILS"), 0u) << r;
  for (const auto& line : lines_of(r.out))
    for (const char* property : {"energy conservation", "reciprocity", "non-negativity"})
      if (line.find(property) != std::string::npos) {
        EXPECT_THAT(line, HasSubstr("holds")) << line;
      }
}

TEST_F(Cli, CheckBarePhongFailsWithExitOne) {
  // k = 1, n = 1: ρ(0) = 2π ∫ cos² θ sin θ dθ = 2π/3 > 1.
  const Result r = run({"check", "--model", "phong", "-p", "n=1", "--step", "30", "--pairs", "500"});
  EXPECT_EQ(r.code, 1) << r;
  EXPECT_THAT(r.err, IsEmpty());
  EXPECT_THAT(r.out, HasSubstr("FAILS"));
  bool seen = false;
  for (const auto& line : lines_of(r.out)) {
    if (line.find("energy conservation") != std::string::npos) {
      EXPECT_THAT(line, HasSubstr("FAILS")) << line;
    }
    if (line.find("reciprocity") != std::string::npos) {
      EXPECT_THAT(line, HasSubstr("holds")) << line;
    }
    const std::string label = "albedo at normal incidence";
    if (const auto at = line.find(label); at != std::string::npos) {
      std::string value = line.substr(at + label.size());
      value.erase(0, value.find_first_not_of(' '));
      EXPECT_NEAR(number(value), 2 * kPi / 3, 1e-9) << line;
      seen = true;
    }
  }
  EXPECT_TRUE(seen) << r;
}

TEST_F(Cli, CheckKMadeForRvFailsInNhAndTheNhCoefficientHolds) {
  const std::vector<std::string> args{"check", "--model", "log-normalized", "-p", "n=20", "--form", "nh",
                                      "--step", "30", "--pairs", "500"};
  const Result fails = run(args);
  EXPECT_EQ(fails.code, 1) << fails;
  EXPECT_THAT(fails.err, IsEmpty());
  EXPECT_THAT(fails.out, HasSubstr("FAILS"));

  const double k = only(parse_csv(ok({"normalize", "--model", "log", "--form", "nh", "--n", "20"}).out), "coef");
  std::vector<std::string> with_coef = args;
  with_coef.insert(with_coef.end(), {"--coef", fmt::format("{}", k), "--json"});
  const Result r = ok(with_coef);
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r;
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 1u);
  const auto& e = j[0];
  EXPECT_EQ(e["model"], "log-normalized");
  EXPECT_EQ(e["form"], "nh");
  for (const char* key : {"conserves_energy", "reciprocal", "non_negative"}) {
    ASSERT_TRUE(e.contains(key) && e[key].is_boolean()) << key << "\n" << e.dump(2);
    EXPECT_TRUE(e[key].get<bool>()) << key;
  }
  for (const char* key : {"max_albedo", "max_albedo_theta_deg", "albedo_normal"})
    ASSERT_TRUE(e.contains(key) && e[key].is_number()) << key << "\n" << e.dump(2);
  EXPECT_NEAR(e["albedo_normal"].get<double>(), 1.0, 1e-8);
  EXPECT_NEAR(e["max_albedo"].get<double>(), 1.0, 1e-7);
  EXPECT_GE(e["max_albedo_theta_deg"].get<double>(), 0.0);
  EXPECT_LT(e["max_albedo_theta_deg"].get<double>(), 90.0);
}

TEST_F(Cli, CheckSweepsAParameter) {
  // Ward (√ normalization) at α = 0.3 reflects more than it receives near grazing: exit 1.
  const Result r =
      run({"check", "--model", "ward", "--sweep", "alpha=0.1,0.3", "--step", "30", "--pairs", "200", "--json"});
  EXPECT_THAT(r.code, ::testing::AnyOf(0, 1)) << r;
  EXPECT_THAT(r.err, IsEmpty());
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r;
  ASSERT_TRUE(j.is_array());
  ASSERT_EQ(j.size(), 2u) << r;
  bool all_hold = true;
  for (const auto& e : j) {
    EXPECT_EQ(e["model"], "ward");
    for (const char* key : {"conserves_energy", "reciprocal", "non_negative"}) {
      ASSERT_TRUE(e.contains(key) && e[key].is_boolean()) << key << "\n" << e.dump(2);
      all_hold = all_hold && e[key].get<bool>();
    }
    EXPECT_TRUE(e["max_albedo"].is_number());
    EXPECT_TRUE(e["max_albedo_theta_deg"].is_number());
    EXPECT_EQ(e["pairs"], 200);
  }
  EXPECT_EQ(r.code, all_hold ? 0 : 1) << r;
  EXPECT_EQ(number(j[0]["alpha"].is_string() ? j[0]["alpha"].get<std::string>() : j[0]["alpha"].dump()), 0.1);
  EXPECT_EQ(number(j[1]["alpha"].is_string() ? j[1]["alpha"].get<std::string>() : j[1]["alpha"].dump()), 0.3);
  EXPECT_TRUE(j[0]["conserves_energy"].get<bool>()) << j[0].dump(2);
  EXPECT_FALSE(j[1]["conserves_energy"].get<bool>()) << j[1].dump(2);
  EXPECT_GT(j[1]["max_albedo"].get<double>(), 1.0);
  EXPECT_GT(j[1]["max_albedo_theta_deg"].get<double>(), 80.0);
}

TEST_F(Cli, CheckBadInput) {
  EXPECT_THAT(bad({"check", "--model", "log", "--n", "1", "--sweep", "n=2"}).err, HasSubstr("--sweep"));
  EXPECT_THAT(bad({"check", "--model", "ward", "--sweep", "alpha"}).err, HasSubstr("alpha"));
  EXPECT_THAT(bad({"check", "--model", "ward", "--sweep", "q=1:2"}).err, HasSubstr("q"));
  EXPECT_THAT(bad({"check", "--model", "ward", "--step", "0"}).err, HasSubstr("--step"));
  EXPECT_THAT(bad({"check", "--model", "ward", "--pairs", "0"}).err, HasSubstr("--pairs"));
  EXPECT_THAT(bad({"check", "--model", "nope"}).err, HasSubstr("nope"));
}

// ---- error ----------------------------------------------------------------------------------

TEST_F(Cli, ErrorOfLogAgainstPhong) {
  // docs/math.md §3: |F_log − c^n| peaks at 1/8 where c^n = 2^−3, for every n; F_log reaches 0 where
  // c^n > 0, so the relative error in the attenuation zone is 1.
  const Csv csv = parse_csv(ok({"error", "--model", "log", "--reference", "phong", "--n", "1,20,1000"}).out);
  EXPECT_THAT(csv.columns,
              ElementsAre("n", "max_abs", "argmax_abs_deg", "max_rel_epicenter", "max_rel_attenuation"));
  ASSERT_EQ(csv.rows.size(), 3u);
  for (const auto& row : csv.rows) {
    const double n = row[0];
    EXPECT_NEAR(row[1], 0.125, 1e-12) << "n = " << n;
    EXPECT_NEAR(row[2], deg_of(std::acos(std::pow(2.0, -3 / n))), 1e-6) << "n = " << n;
    EXPECT_GE(row[3], 0) << "n = " << n;
    EXPECT_EQ(row[4], 1.0) << "n = " << n;
  }
  EXPECT_EQ(csv.rows[0][0], 1.0);
  EXPECT_EQ(csv.rows[2][0], 1000.0);
}

TEST_F(Cli, ErrorOfSchlickAgainstPhongAndTheZone) {
  const std::vector<std::string> args{"error", "--model", "schlick", "--reference", "phong", "--n", "2"};
  const Csv half = parse_csv(ok(args).out);
  EXPECT_NEAR(only(half, "max_abs"), 0.09, 0.005);
  std::vector<std::string> narrow_args = args;
  narrow_args.insert(narrow_args.end(), {"--zone", "0.9"});
  const Csv narrow = parse_csv(ok(narrow_args).out);
  EXPECT_EQ(only(narrow, "max_abs"), only(half, "max_abs"));  // the zone bounds the relative errors only
  // A smaller epicenter (F_ref ≥ 0.9 inside F_ref ≥ 0.5): its max relative error can only drop.
  EXPECT_NE(only(narrow, "max_rel_epicenter"), only(half, "max_rel_epicenter"));
  EXPECT_LT(only(narrow, "max_rel_epicenter"), only(half, "max_rel_epicenter"));
}

TEST_F(Cli, ErrorBadInput) {
  const std::vector<std::string> base{"error", "--model", "log", "--reference", "phong"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  EXPECT_THAT(bad(with({"--n", "20", "--zone", "0"})).err, HasSubstr("zone"));
  EXPECT_THAT(bad(with({"--n", "20", "--zone", "1.5"})).err, HasSubstr("zone"));
  EXPECT_THAT(bad({"error", "--model", "log", "--reference", "ggx", "--n", "20"}).err, HasSubstr("full BRDF"));
  EXPECT_THAT(bad(with({"-p", "n=3"})).err, HasSubstr("--n"));
  EXPECT_THAT(bad(with({"--n", "0"})).err, HasSubstr("0"));
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

// ---- fit ------------------------------------------------------------------------------------

// y = 2.5·x + 0.75/(x + 0.5): exactly a formula of the default operators + * / with constants.
double pole_curve(double x) { return 2.5 * x + 0.75 / (x + 0.5); }
// √x: no formula of + * / is exact, so the front keeps improving with size.
double root_curve(double x) { return std::sqrt(x); }

// 40 points evenly spaced in [0.1, 5].
std::vector<double> fit_xs() {
  std::vector<double> xs;
  for (int i = 0; i < 40; ++i) xs.push_back(0.1 + i * 4.9 / 39);
  return xs;
}

// Columns x and y = f(x), every number written to round-trip exactly.
std::string csv_of(double (*f)(double)) {
  std::string text = "x,y\n";
  for (double x : fit_xs()) text += fmt::format("{},{}\n", x, f(x));
  return text;
}

void expect_candidate(const nlohmann::json& c) {
  ASSERT_TRUE(c.is_object()) << c.dump(2);
  EXPECT_TRUE(c.contains("size") && c["size"].is_number_integer()) << c.dump(2);
  EXPECT_TRUE(c.contains("train_error") && c["train_error"].is_number()) << c.dump(2);
  EXPECT_TRUE(c.contains("test_error") && (c["test_error"].is_null() || c["test_error"].is_number()))
      << c.dump(2);
  EXPECT_TRUE(c.contains("formula") && c["formula"].is_string()) << c.dump(2);
}

// A search of a few seconds even under ASan: few generations of small islands after a short
// enumeration.
std::vector<std::string> small_search(const char* generations) {
  return {"--generations", generations, "--enumerate-size", "5", "--population", "50"};
}

// `specula fit` on a data file of the test's own, target y and variable x, with --time as a cap
// (the budgets are in generations).
class CliFit : public Cli {
 protected:
  /// Writes `text` to a file in work() and returns its path.
  std::string data_file(const std::string& name, const std::string& text) const {
    const fs::path path = work() / name;
    std::ofstream(path) << text;
    return path.string();
  }

  static std::vector<std::string> fit_args(const std::string& data, const std::vector<std::string>& extra) {
    std::vector<std::string> args{"fit", "--data", data, "--target", "y", "--vars", "x", "--time", "30"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }

  /// Runs a fit that must succeed with --format json and returns the parsed output.
  nlohmann::json fit_json(const std::string& data, std::vector<std::string> extra) {
    extra.insert(extra.end(), {"--format", "json"});
    const Result r = ok(fit_args(data, extra));
    nlohmann::json j = nlohmann::json::parse(r.out, nullptr, false);
    EXPECT_FALSE(j.is_discarded()) << r;
    EXPECT_TRUE(j.contains("front") && j["front"].is_array() && !j["front"].empty()) << r;
    EXPECT_TRUE(j.contains("chosen")) << r;
    return j;
  }
};

TEST_F(CliFit, RecoversAKnownFormulaFromNoiselessData) {
  // Stops once the formula is found (in the enumeration, today), else after 20 generations.
  const nlohmann::json j =
      fit_json(data_file("pole.csv", csv_of(pole_curve)), {"--generations", "20", "--target-error", "1e-12"});
  ASSERT_TRUE(j.contains("front") && j.contains("chosen")) << j.dump(2);
  for (const auto& c : j["front"]) expect_candidate(c);
  expect_candidate(j["chosen"]);
  EXPECT_LT(j["chosen"]["train_error"].get<double>(), 1e-9) << j.dump(2);
  // The printed formula alone reproduces the data.
  const auto chosen = specula::expr::parse(j["chosen"]["formula"].get<std::string>(), {"x"});
  for (double x : fit_xs())
    EXPECT_NEAR(specula::expr::evaluate(chosen, std::array{x}), pole_curve(x), 1e-8) << "x = " << x;
}

TEST_F(CliFit, FrontSizesRiseAndTrainErrorsFall) {
  const nlohmann::json j = fit_json(data_file("root.csv", csv_of(root_curve)), small_search("5"));
  ASSERT_TRUE(j.contains("front")) << j.dump(2);
  const auto& front = j["front"];
  EXPECT_GE(front.size(), 3u) << j.dump(2);
  for (std::size_t i = 1; i < front.size(); ++i) {
    EXPECT_GT(front[i]["size"].get<int>(), front[i - 1]["size"].get<int>()) << j.dump(2);
    EXPECT_LT(front[i]["train_error"].get<double>(), front[i - 1]["train_error"].get<double>()) << j.dump(2);
  }
}

TEST_F(CliFit, TestErrorOnlyWithHeldOutRows) {
  const std::string data = data_file("root.csv", csv_of(root_curve));
  std::vector<std::string> with_test_rows = small_search("2");
  with_test_rows.insert(with_test_rows.end(), {"--test-fraction", "0.25"});
  const nlohmann::json held_out = fit_json(data, with_test_rows);
  const nlohmann::json all_rows = fit_json(data, small_search("2"));
  ASSERT_TRUE(held_out.contains("front") && all_rows.contains("front"));
  for (const auto& c : held_out["front"]) EXPECT_TRUE(c["test_error"].is_number()) << c.dump(2);
  EXPECT_TRUE(held_out["chosen"]["test_error"].is_number()) << held_out.dump(2);
  for (const auto& c : all_rows["front"]) EXPECT_TRUE(c["test_error"].is_null()) << c.dump(2);
  EXPECT_TRUE(all_rows["chosen"]["test_error"].is_null()) << all_rows.dump(2);
}

TEST_F(CliFit, SameSeedAndGenerationsGiveTheSameFrontForAnyThreadCount) {
  const std::string data = data_file("root.csv", csv_of(root_curve));
  auto with_threads = [&](const char* threads) {
    std::vector<std::string> extra = small_search("10");
    extra.insert(extra.end(), {"--seed", "7", "--threads", threads});
    return fit_json(data, extra);
  };
  const nlohmann::json one = with_threads("1");
  const nlohmann::json two = with_threads("2");
  EXPECT_EQ(one["stopped_by"], "generations") << one.dump(2);
  EXPECT_EQ(two["stopped_by"], "generations") << two.dump(2);
  EXPECT_EQ(one["front"], two["front"]) << "--threads 1:\n" << one["front"].dump(2) << "\n--threads 2:\n"
                                        << two["front"].dump(2);
}

TEST_F(CliFit, BadDataIsOneLineNamingTheProblem) {
  EXPECT_THAT(bad(fit_args(data_file("empty.csv", ""), {})).err, HasSubstr("empty file"));
  EXPECT_THAT(bad(fit_args(data_file("header.csv", "x,y\n"), {})).err, HasSubstr("no data rows"));
  const std::string good = data_file("good.csv", "x,y\n1,2\n2,3\n3,5\n");
  EXPECT_THAT(bad({"fit", "--data", good, "--target", "z"}).err, HasSubstr("\"z\""));
  const Result nan = bad(fit_args(data_file("nan.csv", "x,y\n1,2\n2,nan\n3,5\n"), {}));
  EXPECT_THAT(nan.err, HasSubstr("line 3"));
  EXPECT_THAT(nan.err, HasSubstr("nan"));
  const Result text = bad(fit_args(data_file("text.csv", "x,y\n1,2\n2,abc\n3,5\n"), {}));
  EXPECT_THAT(text.err, HasSubstr("line 3"));
  EXPECT_THAT(text.err, HasSubstr("column 2"));
  EXPECT_THAT(text.err, HasSubstr("abc"));
}

TEST_F(CliFit, BadOptionsAreOneLineNamingTheProblem) {
  const std::string good = data_file("good.csv", "x,y\n1,2\n2,3\n3,5\n");
  EXPECT_THAT(bad(fit_args(good, {"--metric", "nope"})).err, HasSubstr("nope"));
  EXPECT_THAT(bad(fit_args(good, {"--ops", "+,tan"})).err, HasSubstr("tan"));
  EXPECT_THAT(bad(fit_args(good, {"--test-fraction", "1.5"})).err, HasSubstr("test fraction"));
  EXPECT_THAT(bad(fit_args(good, {"--generations", "-1"})).err, HasSubstr("budgets"));
  EXPECT_THAT(bad(fit_args(good, {"--enumerate-size", "-2"})).err, HasSubstr("--enumerate-size"));
  const std::string zero = data_file("zero.csv", "x,y\n1,0\n2,1\n3,2\n");
  EXPECT_THAT(bad(fit_args(zero, {"--metric", "mean-relative"})).err, HasSubstr("row 1 is 0"));
}

double asin_curve(double x) { return std::asin(0.2 * x); }

// expm1, log1p and asin, the ops added last, in --ops, --size-weights and --help: every size on
// the front is positive and within --max-size (a weight table shorter than the op list once
// printed sizes such as -1269334649 and let larger formulas in).
TEST_F(CliFit, TheLastOperatorsHaveSizesAndWeights) {
  const std::string data = data_file("asin.csv", csv_of(asin_curve));
  for (const char* weights : {"default", "asin=2", "expm1=3,log1p=2,asin=4"}) {
    std::vector<std::string> extra = small_search("3");
    extra.insert(extra.end(), {"--ops", "+,*,/,asin,expm1,log1p", "--size-weights", weights,
                               "--max-size", "12"});
    const nlohmann::json j = fit_json(data, extra);
    for (const auto& c : j["front"]) {
      EXPECT_GE(c["size"].get<int>(), 1) << weights << "\n" << j.dump(2);
      EXPECT_LE(c["size"].get<int>(), 12) << weights << "\n" << j.dump(2);
    }
  }
  const std::string help = ok({"fit", "--help"}).out;
  for (const char* op : {"expm1", "log1p", "asin"}) EXPECT_THAT(help, HasSubstr(op));
}

// Names are checked before the search starts, not after its budget.
TEST_F(CliFit, BadColumnNamesFailBeforeSearching) {
  const std::string dash = data_file("dash.csv", "a-b,y\n1,2\n2,3\n");
  EXPECT_THAT(bad({"fit", "--data", dash, "--target", "y", "--time", "600"}).err,
              HasSubstr("invalid variable name 'a-b'"));
  const std::string keyword = data_file("keyword.csv", "double,y\n1,2\n2,3\n");
  EXPECT_THAT(bad({"fit", "--data", keyword, "--target", "y", "--emit", "cpp", "--time", "600"}).err,
              HasSubstr("reserved word in cpp"));
  const std::string odd_target = data_file("odd.csv", "x,coef-1\n1,2\n2,3\n");
  std::vector<std::string> args{"fit", "--data", odd_target, "--target", "coef-1", "--emit", "cpp"};
  for (const auto& a : small_search("1")) args.push_back(a);
  EXPECT_THAT(ok(args).out, HasSubstr("double fitted_coef_1(double x)"));
}

TEST_F(CliFit, EmitsTheChosenFormulaAsCode) {
  const std::string data = data_file("pole.csv", csv_of(pole_curve));
  auto emitting = [&](const char* language) {
    std::vector<std::string> extra = small_search("2");
    extra.insert(extra.end(), {"--emit", language});
    return ok(fit_args(data, extra));
  };
  const Result cpp = emitting("cpp");
  EXPECT_THAT(cpp.out, HasSubstr("double fitted_y(double x) {"));
  const Result glsl = emitting("glsl");
  EXPECT_THAT(glsl.out, HasSubstr("with float constants (double: "));
  EXPECT_THAT(cpp.out, ::testing::Not(HasSubstr("float constants")));  // negative control: C++ keeps doubles
  const Result python = emitting("python");
  EXPECT_THAT(python.out, ::testing::StartsWith("import math\n"));
  EXPECT_THAT(python.out, HasSubstr("def fitted_y(x):"));
}

TEST_F(CliFit, OutWritesTheFileAndNothingElse) {
  const std::string data = data_file("pole.csv", csv_of(pole_curve));
  const fs::path file = work() / "front.json";
  std::vector<std::string> extra = small_search("2");
  extra.insert(extra.end(), {"--format", "json", "--out", file.string()});
  const Result r = ok(fit_args(data, extra));
  EXPECT_THAT(r.out, IsEmpty());
  const nlohmann::json j = nlohmann::json::parse(read_file(file), nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << read_file(file);
  EXPECT_TRUE(j.contains("front") && j["front"].is_array() && !j["front"].empty()) << j.dump(2);
  EXPECT_THAT(listing(work()), ElementsAre("front.json", "pole.csv"));
}

// ---- bench ----------------------------------------------------------------------------------

TEST_F(Cli, BenchQuickJsonHoldsEveryLobeAndTier) {
  // The figures themselves are timings of this machine: only their presence and sign are
  // checked, and the accuracies against the bounds simd/lobes.h states.
  const Result r = ok({"bench", "--quick", "--format", "json"});
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r;
  EXPECT_FALSE(j["machine"]["target"].get<std::string>().empty());
  EXPECT_GT(j["machine"]["peak_vector_fma_per_s"].get<double>(), 0);
  EXPECT_GT(j["machine"]["copy_bytes_per_s"].get<double>(), 0);
  for (const char* lobe : {"power", "schlick", "schlick-modified", "gauss", "log"})
    for (const char* tier : {"scalar", "exact", "fast"}) {
      const auto& t = j["lobes"][lobe][tier];
      EXPECT_GT(t["evals_per_s_per_core"].get<double>(), 0) << lobe << " " << tier;
      EXPECT_GT(t["double"]["ns_per_eval"]["stream_all_cores"].get<double>(), 0) << lobe << " " << tier;
      const double rel = t["max_rel_error"];
      EXPECT_LE(rel, std::string(tier) == "exact" ? 6 * 0x1p-23 : 1e-4) << lobe << " " << tier;  // ULP ≤ 5 (float)
    }
  EXPECT_NEAR(j["lobes"]["log"]["max_abs_error_vs_power"].get<double>(), 0.125, 1e-6);  // docs/math.md §3
  EXPECT_EQ(j["lobes"]["power"]["max_abs_error_vs_power"].get<double>(), 0);
  EXPECT_GT(j["lobes"]["log"]["fast"]["float"]["ops_per_value"].get<double>(), 0);
}

TEST_F(Cli, BenchMeasuresUserLobesBesideTheBuiltIns) {
  // --models FILE: a user lobe gets the three paths, with finite times, beside the built-ins; a
  // full BRDF is no lobe. (One lobe of builtin-copies.toml: every bench run times every row.)
  const fs::path models = work() / "models.toml";
  std::ofstream(models) << R"toml([[model]]
id = "my-log"
name = "log lobe, my copy"
kind = "lobe"
form = "rv"
lobe = "max(0, 1 - 0.5*log2(1 - n*log2(c)))"
normalization = "none"
[model.params.n]
default = 20
min = 0
min_exclusive = true
max = 1e9

[[model]]
id = "my-lambert"
name = "Lambert, a user's copy"
kind = "brdf"
brdf = "rho/pi"
[model.params.rho]
default = 1
min = 0
max = 1
)toml";
  const Result r = ok({"--models", models.string(), "bench", "--quick", "--format", "json"});
  nlohmann::json j;
  ASSERT_NO_THROW(j = nlohmann::json::parse(r.out)) << r;
  ASSERT_TRUE(j["lobes"].contains("my-log")) << r.out;
  EXPECT_TRUE(j["lobes"]["my-log"]["user_model"].get<bool>());
  EXPECT_FALSE(j["lobes"]["log"]["user_model"].get<bool>());
  EXPECT_FALSE(j["lobes"].contains("my-lambert"));
  for (const char* tier : {"scalar", "exact", "fast"}) {
    const auto& t = j["lobes"]["my-log"][tier];
    EXPECT_GT(t["evals_per_s_per_core"].get<double>(), 0) << tier;
    EXPECT_GT(t["double"]["ns_per_eval"]["cache"].get<double>(), 0) << tier;
    EXPECT_GT(t["float"]["ns_per_eval"]["stream"].get<double>(), 0) << tier;
  }
  EXPECT_LE(j["lobes"]["my-log"]["fast"]["max_rel_error"].get<double>(), 1e-4);
  EXPECT_LE(j["lobes"]["my-log"]["exact"]["max_rel_error"].get<double>(), 0x1p-24 + 16 * 0x1p-52);
  EXPECT_NEAR(j["lobes"]["my-log"]["max_abs_error_vs_power"].get<double>(), 0.125, 1e-6);  // as the built-in's
}

TEST_F(Cli, BenchTableHasRatiosBaselinesAndLimits) {
  const Result r = ok({"bench", "--quick", "--n", "50"});
  EXPECT_THAT(r.out, HasSubstr("every lobe at n = 50"));
  EXPECT_THAT(r.out, HasSubstr("× libm"));
  EXPECT_THAT(r.out, HasSubstr("baselines (float, in cache, one core): cⁿ through libm"));
  EXPECT_THAT(r.out, HasSubstr("limits: compute = ops/value"));
  bad({"bench", "--format", "xml"});
  bad({"bench", "--n", "0"});
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
        {"normalize", "--help"}, {"report", "--help"}, {"albedo", "--help"},
        {"check", "--help"}, {"error", "--help"}, {"fit", "--help"}, {"export", "--help"}}) {
    const Result r = run(args);
    const std::string what = fmt::format("specula {}", fmt::join(args, " "));
    EXPECT_EQ(r.code, 0) << what << "\n" << r;
    EXPECT_THAT(r.out, HasSubstr("Example")) << what;
  }
}

// ---- version --------------------------------------------------------------------------------

// --version and -V: one line for bug reports, exit 0, nothing on stderr: the version
// (project(VERSION)), the commit (cmake/build_info.cmake; "unknown" outside a git checkout) and
// Highway's dispatched target, also with --models and before a subcommand.
TEST_F(Cli, VersionIsOneLine) {
  const std::string line = ok({"--version"}).out;
  EXPECT_THAT(line, MatchesRegex("specula [0-9]+\\.[0-9]+\\.[0-9]+ \\(commit ([0-9a-f]+|unknown)\\), "
                                 "SIMD: [A-Z0-9_]+\n"));
  EXPECT_EQ(ok({"-V"}).out, line);
  EXPECT_EQ(ok({"--version", "models"}).out, line);
}

// ---- export ---------------------------------------------------------------------------------

TEST_F(Cli, ExportWritesEachFormat) {
  EXPECT_THAT(ok({"export", "--model", "ggx", "-p", "alpha=0.2", "--format", "hlsl"}).out,
              HasSubstr("float specula_ggx(float3 N, float3 L, float3 V, float alpha, float f0)"));
  EXPECT_THAT(ok({"export", "--model", "ggx", "--format", "msl"}).out, HasSubstr("metal::normalize(L + V)"));
  EXPECT_THAT(ok({"export", "--model", "log-normalized", "-p", "n=50", "--format", "brdf"}).out,
              HasSubstr("::begin parameters\nfloat n 1 1000 50\n::end parameters\n"));
  EXPECT_THAT(ok({"export", "--model", "lobe: c^n", "-p", "n=8", "--coef", "3.5", "--format", "cpp"}).out,
              HasSubstr("return 3.5 * specula_lobe_c_n_lobe(specula_cos_rv(N, L, V), p_n);"));
  EXPECT_THAT(ok({"export", "--model", "ggx+ms", "-p", "alpha=0.5", "--format", "cpp"}).out,
              HasSubstr("return p * base::model_pdf(wi, wo) + (1 - p) * wo.z / kPi;"));
  EXPECT_THAT(ok({"export", "--model", "lobe: c^n", "--coef", "1e308", "--format", "cpp"}).out, HasSubstr("1e+308 * "));
  const fs::path file = work() / "log.brdf";
  EXPECT_THAT(ok({"export", "--model", "log", "--format", "brdf", "--out", file.string()}).out, IsEmpty());
  EXPECT_EQ(read_file(file).rfind("analytic\n", 0), 0u);
  EXPECT_THAT(listing(work()), ElementsAre("log.brdf"));
}

TEST_F(Cli, ExportBadInput) {
  EXPECT_THAT(bad({"export", "--model", "ggx", "--format", "spirv"}).err, HasSubstr("unknown export format 'spirv'"));
  bad({"export", "--model", "ggx"});
  bad({"export", "--model", "nope", "--format", "cpp"});
  bad({"export", "--model", "ggx", "--form", "nh", "--format", "cpp"});
  bad({"export", "--model", "log", "-p", "n=0", "--format", "hlsl"});
  // A coefficient a double holds and a float does not: the shading languages refuse it.
  for (const char* format : {"hlsl", "msl", "brdf"})
    EXPECT_THAT(bad({"export", "--model", "lobe: c^n", "--coef", "1e308", "--format", format}).err,
                HasSubstr("a float holds at most 3.4028235e+38"));
  EXPECT_THAT(listing(work()), IsEmpty());
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

// `specula report --quick` itself (its files, its stdout and stderr) is checked by
// tests/report/report_page_test.cpp, which runs it once for all its tests.
TEST_F(Cli, ReportIntoAFileFails) {
  const fs::path file = work() / "afile";
  std::ofstream(file) << "x";
  const Result r = bad({"report", "--out", file.string()});
  EXPECT_THAT(r.err, HasSubstr(file.string()));
  EXPECT_THAT(listing(work()), ElementsAre("afile"));
}

}  // namespace
