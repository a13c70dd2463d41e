// The report: writes a self-contained page with the paper's Fig. 5 and its table as CSV.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <numbers>
#include <sstream>

#include "specula/exceptions.h"
#include "specula/expr/expr.h"
#include "specula/models/model.h"
#include "specula/catalogue/model_file.h"
#include "specula/normalize/normalize.h"
#include "specula/report/report.h"
#include "report/quick_report.h"
#include "text_support.h"

namespace specula::report {
namespace {

using specula::testing::cells_of;
using specula::testing::lines_of;
using specula::testing::read_file;

class ReportTest : public ::testing::Test {
 protected:
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("specula-report-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                               "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(ReportTest, RefusesAnOutputThatIsAFile) {
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "file") << "x";
  EXPECT_THROW(write_report({dir / "file"}), InvalidArgument);
}


// The paper's figures and the sections beyond it, from the quick report that the report suites
// share (quick_report.h: `specula --models tests/report/user_lobes.toml report --quick`, made once
// per ctest run by the fixture report.quick_report). The user's lobes are registered here too, so
// that models() lists what the report's CLI saw.
class BeyondThePaperTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    register_model_file(SPECULA_SOURCE_DIR "/tests/report/user_lobes.toml");
    const specula::testing::QuickReport report = specula::testing::quick_report();
    dir_ = new std::filesystem::path(report.dir);
    sections_ = new std::vector<std::string>;
    for (const auto& line : lines_of(report.err))
      if (line.starts_with("report: ")) sections_->push_back(line.substr(8));
    html_ = new std::string(read_file(*dir_ / "index.html"));
  }
  static void TearDownTestSuite() {
    clear_registered_models();
    delete dir_;
    delete html_;
    delete sections_;
  }

  static const std::filesystem::path& dir() { return *dir_; }
  static const std::vector<std::string>& sections() { return *sections_; }
  static const std::string& html() { return *html_; }

  /// The HTML of the section `id`.
  static std::string section(const std::string& id) {
    const auto start = html().find("<section id=\"" + id + "\">");
    if (start == std::string::npos) return "";
    return html().substr(start, html().find("</section>", start) - start);
  }

  /// The cells (inner HTML) of the first table row of `text` that starts with `first_cells`.
  static std::vector<std::string> row(const std::string& text, const std::vector<std::string>& first_cells) {
    std::string prefix = "<tr>";
    for (const auto& cell : first_cells) prefix += "<td>" + cell + "</td>";
    const auto start = text.find(prefix);
    if (start == std::string::npos) return {};
    const std::string tr = text.substr(start, text.find("</tr>", start) - start);
    std::vector<std::string> cells;
    for (auto at = tr.find("<td"); at != std::string::npos; at = tr.find("<td", at + 1)) {
      const auto open_end = tr.find('>', at) + 1;
      cells.push_back(tr.substr(open_end, tr.find("</td>", open_end) - open_end));
    }
    return cells;
  }

  /// The rows of a CSV file beside the page, header first.
  static std::vector<std::vector<std::string>> csv(const std::string& name) {
    std::vector<std::vector<std::string>> rows;
    for (const auto& line : lines_of(read_file(dir() / name))) rows.push_back(cells_of(line));
    return rows;
  }

 private:
  static inline std::filesystem::path* dir_ = nullptr;
  static inline std::string* html_ = nullptr;
  static inline std::vector<std::string>* sections_ = nullptr;
};

TEST_F(BeyondThePaperTest, WritesFig5WithThePapersRowsMatched) {
  EXPECT_FALSE(sections().empty());  // progress, section by section
  EXPECT_NE(html().find("Fig. 5"), std::string::npos);
  EXPECT_NE(html().find("<td>0.483</td><td>0.483</td>"), std::string::npos);
  EXPECT_NE(html().find("<td>1.634</td><td>1.634</td>"), std::string::npos);
  EXPECT_EQ(html().find(">differs</td>"), std::string::npos);  // the verdict cell of a Fig. 5 row
  EXPECT_EQ(html().find("http://"), std::string::npos);   // self-contained: no external references
  EXPECT_EQ(html().find("https://"), std::string::npos);
  EXPECT_EQ(html().find("<script src"), std::string::npos);

  const std::string csv = read_file(dir() / "fig5-normalization.csv");
  EXPECT_EQ(csv.rfind("n,coef_exact,coef_exact_3dp,coef_paper_fit,delta_paper_fit\n1,", 0), 0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 51);
  EXPECT_NE(csv.find("\n1000,197.498610080195"), std::string::npos);
}

TEST_F(BeyondThePaperTest, HasTheThreeSectionsWithTheirFigures) {
  for (const char* id : {"energy", "fitted-norms", "cost"}) {
    EXPECT_NE(html().find(fmt::format("<section id=\"{}\">", id)), std::string::npos) << id;
    EXPECT_NE(html().find(fmt::format("<a href=\"#{}\">", id)), std::string::npos) << id;  // in the contents
  }
  for (const char* figure : {"energy-albedo-rv", "energy-albedo-nh", "energy-albedo-brdfs", "fitted-norms-published",
                             "fitted-norms-own", "cost-accuracy"}) {
    EXPECT_NE(html().find(fmt::format("<figure id=\"{}\">\n<svg", figure)), std::string::npos) << figure;
    EXPECT_TRUE(std::filesystem::exists(dir() / (std::string(figure) + ".svg"))) << figure;
  }
  for (const char* table : {"energy-albedo", "energy-check", "energy-polar", "fitted-norms-published",
                            "fitted-norms-formulas", "fitted-norms-check", "cost"}) {
    EXPECT_TRUE(std::filesystem::exists(dir() / (std::string(table) + ".csv"))) << table;
    EXPECT_TRUE(std::filesystem::exists(dir() / (std::string(table) + ".json"))) << table;
  }
  // The sections sit after the paper's figures and before the end; the claims stay first.
  EXPECT_LT(html().find("<section id=\"claims\">"), html().find("<section id=\"normalization\">"));
  EXPECT_LT(html().find("<section id=\"normalization\">"), html().find("<section id=\"energy\">"));
  EXPECT_LT(html().find("<section id=\"energy\">"), html().find("<section id=\"fitted-norms\">"));
  EXPECT_LT(html().find("<section id=\"fitted-norms\">"), html().find("<section id=\"cost\">"));
}

TEST_F(BeyondThePaperTest, PolarPlotsOfTheLobesAreInAGrid) {
  const std::string energy = section("energy");
  const auto grid = energy.find("<div class=\"grid\">");
  ASSERT_NE(grid, std::string::npos);
  for (const char* figure : {"energy-polar-0", "energy-polar-30", "energy-polar-60"})
    EXPECT_GT(energy.find(fmt::format("<figure id=\"{}\">", figure)), grid) << figure;
  for (const char* id : {"log-normalized", "phong-normalized", "blinn-phong-normalized", "schlick-normalized", "ggx"})
    EXPECT_NE(read_file(dir() / "energy-polar-30.svg").find(fmt::format(">{}</text>", id)), std::string::npos) << id;
}

TEST_F(BeyondThePaperTest, PolarValuesAreTheNormalizedPhongLobeAtNormalIncidence) {
  // With L = N, R·V = cos θ_o: f·cos θ_o = (n + 2)/(2π) cos^(n+1) θ_o, independently of the library.
  const auto rows = csv("energy-polar.csv");
  ASSERT_GT(rows.size(), 100u);
  ASSERT_EQ(rows[0][3], "phong-normalized");
  int checked = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    if (std::stod(rows[i][0]) != 0) continue;
    const double theta_o = std::stod(rows[i][1]) * std::numbers::pi / 180, n = 20;
    const double expected = (n + 2) / (2 * std::numbers::pi) * std::pow(std::cos(theta_o), n + 1);
    EXPECT_NEAR(std::stod(rows[i][3]), expected, 1e-12) << rows[i][1];
    ++checked;
  }
  EXPECT_GT(checked, 100);
}

TEST_F(BeyondThePaperTest, EnergyTableGivesEachModelItsVerdict) {
  const std::string energy = section("energy");
  const auto log = row(energy, {"log-normalized", "rv", "rv"});
  ASSERT_EQ(log.size(), 9u);
  EXPECT_EQ(log[8].rfind("conserves", 0), 0u) << log[8];
  EXPECT_EQ(log[3], "1");  // ρ(0°) = 1 to the 6 digits shown: the exact coefficient, docs/math.md §4
  const auto ct = row(energy, {"cook-torrance-1982", "—", "—"});
  ASSERT_EQ(ct.size(), 9u);
  EXPECT_EQ(ct[8].rfind("gains energy (max ρ = ", 0), 0u) << ct[8];
  EXPECT_GT(std::stod(ct[4]), 3.9);  // about 4× (docs/math.md §2)
  for (const auto& info : models())
    EXPECT_FALSE(row(energy, {std::string(info.id), info.kind == ModelKind::lobe ? to_string(info.form) : "—"}).empty())
        << info.id;
}

TEST_F(BeyondThePaperTest, AlbedosMatchClosedForms) {
  const std::string energy = section("energy");
  const double n = 20;
  // Lafortune's k = (n + 1)/(2π) on Phong's exactly normalized lobe: ρ(0°) = (n + 1)/(n + 2).
  EXPECT_EQ(row(energy, {"phong-lafortune", "rv", "rv"})[3], fmt::format("{:.6g}", (n + 1) / (n + 2)));
  // Phong's rv k used in nh: ρ(0°) = k_rv / k_nh, both closed forms (docs/math.md §2).
  const double phong_in_nh = lobes::phong_rv(n) / lobes::blinn_phong_nh(n);
  EXPECT_EQ(row(energy, {"phong-normalized", "nh", "rv"})[3], fmt::format("{:.6g}", phong_in_nh));
  // Lambert's ρ is its albedo at every angle.
  EXPECT_EQ(row(energy, {"lambert", "—", "—"})[3], "1");
}

// The user's lobes of tests/report/user_lobes.toml, against the mpmath values of
// tests/reference/user_lobes.csv (quartic: k_rv(10) = 2.1315394164093125326, k_nh(10) =
// 0.70036657473796054352; max |F − c¹| at n = 1 = 0.31640625).
TEST_F(BeyondThePaperTest, UserLobesAppearInTheEnergyTable) {
  const std::string energy = section("energy");
  const auto own = row(energy, {"quartic", "rv", "rv"});
  ASSERT_EQ(own.size(), 9u);
  EXPECT_EQ(own[3], "1");  // k by quadrature: ρ(0°) = 1 to the digits shown
  EXPECT_EQ(own[8].rfind("conserves", 0), 0u) << own[8];
  EXPECT_EQ(row(energy, {"quartic", "nh", "rv"})[3], fmt::format("{:.6g}", 2.1315394164093125326 / 0.70036657473796054352));
  EXPECT_NE(row(energy, {"lobe-c8", "rv", "—"})[3], "1");  // control: a bare lobe is not normalized
}

TEST_F(BeyondThePaperTest, UserLobesAreComparedWithCosN) {
  const std::string lobes = section("lobes");
  EXPECT_NE(lobes.find("<figure id=\"user-lobe-errors\">"), std::string::npos);
  EXPECT_FALSE(row(lobes, {"quartic"}).empty());
  EXPECT_TRUE(row(lobes, {"lobe-c8"}).empty());  // no n to sweep
  const auto rows = csv("user-lobe-errors.csv");
  ASSERT_EQ(rows[0][2], "max_abs");
  ASSERT_EQ(rows[1][0], "quartic");
  ASSERT_EQ(std::stod(rows[1][1]), 1.0);
  EXPECT_NEAR(std::stod(rows[1][2]), 0.31640625, 1e-9);
}

TEST_F(BeyondThePaperTest, ClaimsTableReadsTheEnergyFindings) {
  const std::string claims = section("claims");
  EXPECT_NE(claims.find("confirmed at every incidence angle"), std::string::npos);
  EXPECT_NE(claims.find(fmt::format("ρ(0°) = {} at n = 20", fmt::format("{:.6g}", 21.0 / 22))), std::string::npos);
  EXPECT_NE(claims.find("reflects more energy than it receives"), std::string::npos);
}

TEST_F(BeyondThePaperTest, PublishedFormulasAgainstExactCoefficients) {
  // Lafortune's k against the exact Phong k is −1/(n + 2) at every n; (n + 8)/(8π) against Giesen's.
  const auto rows = csv("fitted-norms-published.csv");
  ASSERT_EQ(rows[0][3], "rel_diff_phong_lafortune");
  ASSERT_EQ(rows[0][2], "rel_diff_blinn_phong_approx");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double n = std::stod(rows[i][0]);
    EXPECT_NEAR(std::stod(rows[i][3]), -1 / (n + 2), 1e-14) << n;
    EXPECT_NEAR(std::stod(rows[i][2]), (n + 8) / (8 * std::numbers::pi) / lobes::blinn_phong_nh(n) - 1, 1e-14) << n;
  }
}

TEST_F(BeyondThePaperTest, FittedFormulasHoldTheirStatedError) {
  // Each formula, parsed back from the CSV, against quadrature at the ends of [1, 1000] (on the check grid):
  // within the error the table states for it.
  const auto rows = csv("fitted-norms-formulas.csv");
  ASSERT_EQ(rows.size(), 6u);
  ASSERT_EQ(rows[0][2], "formula");
  const std::string own = section("fitted-norms");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const Form form = parse_form(rows[i][1]);
    const expr::Expression formula = expr::parse(rows[i][2], {"n"});
    const double stated = std::stod(rows[i][5]);
    for (const double n : {1.0, 1000.0}) {
      const double k = normalize::coefficient(make_model(rows[i][0], {{"n", n}}, form).lobe(), form,
                                              normalize::Method::quadrature);
      EXPECT_LE(std::abs(expr::evaluate(formula, std::span<const double>(&n, 1)) / k - 1), stated * (1 + 1e-9))
          << rows[i][0] << " " << rows[i][1] << " n = " << n;
    }
    EXPECT_NE(own.find("<code>" + rows[i][2] + "</code>"), std::string::npos) << rows[i][2];
  }
}

TEST_F(BeyondThePaperTest, MeasuresEveryCompensationAgainstTheWalk) {
  const std::string compensation = section("compensation");
  ASSERT_FALSE(compensation.empty());
  for (const char* name : {"none", "kulla-conty", "turquin-f0", "turquin-f", "turquin-favg", "cycles", "walk-fit", "ggx+ms"})
    EXPECT_NE(compensation.find(fmt::format("<tr><td><code>{}</code></td>", name)), std::string::npos) << name;
  EXPECT_NE(compensation.find("<figure id=\"compensation-grazing\">\n<svg"), std::string::npos);
  const auto rows = csv("compensation-verdict.csv");
  ASSERT_EQ(rows.size(), 1u + 5 * 8);  // five Fresnel families, seven compensations and what ships
  EXPECT_EQ(rows[0], (std::vector<std::string>{"family", "compensation", "max_error", "rms_error", "max_relative_ms",
                                               "max_walk_se", "cells"}));
  for (std::size_t r = 1; r < rows.size(); ++r) {
    if (rows[r][1] == "ggx+ms") {  // +ms on every family: within 0.01 for Schlick's, 0.016 for the rest
      EXPECT_NE(rows[r][6], "0") << rows[r][0];
      EXPECT_LT(std::stod(rows[r][2]), rows[r][0] == "schlick" ? 0.01 : 0.016) << rows[r][0];
      continue;
    }
    EXPECT_LT(std::stod(rows[r][5]), 1e-3) << rows[r][0] << " " << rows[r][1];  // the walk is the reference
    if (rows[r][1] == "none") {
      if (rows[r][0] != "dielectric") {
        EXPECT_GT(std::stod(rows[r][2]), 0.3) << rows[r][0];  // uncompensated
      }
    } else {
      EXPECT_LT(std::stod(rows[r][2]), 0.1) << rows[r][0] << " " << rows[r][1];
    }
  }
  // Every (α, μ) cell of the quick grid (3 × 3) for each of the sixteen Fresnel channels.
  EXPECT_EQ(csv("compensation-cells.csv").size(), 1u + 9 * 16);
}

// The engine terms designed: each term's front against its exact term with the engines' own
// approximations as rows, measured in that run (Schlick's Fresnel 0.113, the fast Smith form 0.214,
// EnvBRDFApprox's B 0.163), and each front's figure beside the page.
TEST_F(BeyondThePaperTest, DesignsTheEnginesTermsBesideTheirApproximations) {
  const std::string terms = section("terms");
  ASSERT_FALSE(terms.empty());
  EXPECT_NE(html().find("<a href=\"#terms\">"), std::string::npos);
  const std::vector<std::pair<std::string, std::string>> expected{
      {"fresnel-dielectric", "schlick"}, {"smith-g2-ggx", "fast-smith"}, {"env-brdf-b-ggx", "lazarov"}};
  for (const auto& [target, reference] : expected) {
    EXPECT_NE(terms.find("<h3>" + target + "</h3>"), std::string::npos) << target;
    EXPECT_TRUE(std::filesystem::exists(dir() / ("designed-" + target + ".svg"))) << target;
    EXPECT_FALSE(row(terms, {reference}).empty()) << reference;
  }
  EXPECT_EQ(row(terms, {"schlick"}).at(1), "0.113");
  EXPECT_EQ(row(terms, {"fast-smith"}).at(1), "0.2142");
  EXPECT_EQ(row(terms, {"lazarov"}).at(1), "0.1627");
  EXPECT_TRUE(row(terms, {"unreal-exp3"}).empty());  // the control: a row that is not there is not found
}

TEST_F(BeyondThePaperTest, CostTableListsEveryModel) {
  const std::string cost = section("cost");
  for (const auto& info : models()) {
    const auto cells = row(cost, {std::string(info.id), to_string(info.kind)});
    ASSERT_EQ(cells.size(), 5u) << info.id;
    EXPECT_GT(std::stod(cells[3]), 0) << info.id;  // a time, never asserted beyond being one
  }
  // The log lobe's largest |F − cⁿ| is 1/8 for every n (docs/math.md §3); Phong's own lobe is exact.
  EXPECT_EQ(row(cost, {"log-normalized", "lobe"})[4], "0.125");
  EXPECT_EQ(row(cost, {"phong", "lobe"})[4], "0");
  EXPECT_EQ(row(cost, {"ggx", "brdf"})[4], "—");
  EXPECT_NE(cost.find("of the machine that wrote this report"), std::string::npos);
  // The user's lobes (tests/report/user_lobes.toml) through the benchmark's three paths too.
  for (const char* path : {"scalar", "exact", "fast"}) {
    EXPECT_EQ(row(cost, {"quartic", path}).size(), 7u) << path;
    EXPECT_EQ(row(cost, {"lobe-c8", path}).size(), 7u) << path;
  }
  EXPECT_NE(read_file(dir() / "cost-accuracy.svg").find(">quartic</text>"), std::string::npos);
}

}  // namespace
}  // namespace specula::report
