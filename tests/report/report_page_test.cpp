// `specula report --quick` as a user runs it: the page parses in a real browser (headless
// Chromium), holds every section and figure and no external reference, renders to a non-blank
// screenshot, and its claims table quotes the same numbers as the analysis commands.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "specula/render/image_io.h"
#include "report/quick_report.h"
#include "text_support.h"

namespace specula::report {
namespace {

namespace fs = std::filesystem;
using specula::testing::read_file;

struct Command {
  int exit_code;
  std::string out, err;
};

Command run(const std::string& command) {
  const fs::path out = fs::temp_directory_path() / fmt::format("specula-page-{}.out", ::getpid());
  const fs::path err = fs::temp_directory_path() / fmt::format("specula-page-{}.err", ::getpid());
  const int status = std::system(fmt::format("{} > '{}' 2> '{}'", command, out.string(), err.string()).c_str());
  Command r{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(out), read_file(err)};
  fs::remove(out);
  fs::remove(err);
  return r;
}

std::string chromium(const fs::path& profile, const std::string& arguments) {
  return fmt::format("timeout 120 '{}' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
                     "--disable-background-networking --disable-component-update --disable-sync "
                     "--user-data-dir='{}' {}",
                     SPECULA_CHROMIUM, profile.string(), arguments);
}

// The quick report that the report suites share (quick_report.h: made once per ctest run by the
// fixture report.quick_report); this suite's own files (browser profiles, screenshots) go to a
// scratch folder of its own.
class ReportPage : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / fmt::format("specula-report-page-{}", ::getpid()));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    report_ = new specula::testing::QuickReport(specula::testing::quick_report());
    html_ = new std::string(read_file(report_->dir / "index.html"));
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
    delete report_;
    delete html_;
  }
  static const std::string& html() { return *html_; }
  static const specula::testing::QuickReport& made() { return *report_; }
  static fs::path out() { return report_->dir; }
  static fs::path scratch() { return *dir_; }

  static fs::path* dir_;
  static specula::testing::QuickReport* report_;
  static std::string* html_;
};

fs::path* ReportPage::dir_ = nullptr;
specula::testing::QuickReport* ReportPage::report_ = nullptr;
std::string* ReportPage::html_ = nullptr;

std::set<std::string> ids_of(const std::string& text, const std::string& element) {
  std::set<std::string> ids;
  const std::regex id("<" + element + " id=\"([^\"]+)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), id); it != std::sregex_iterator(); ++it)
    ids.insert((*it)[1]);
  return ids;
}

TEST_F(ReportPage, RunsWithProgressPerSectionOnStderr) {
  ASSERT_EQ(made().exit_code, 0) << made().err;
  EXPECT_EQ(made().out, "");
  EXPECT_NE(made().err.find("report: Figs. 2-4"), std::string::npos) << made().err;
  EXPECT_NE(made().err.find("report: Fig. 9"), std::string::npos) << made().err;
  EXPECT_NE(made().err.find("wrote"), std::string::npos);
}

TEST_F(ReportPage, WritesFig5WithItsFiftyRowsAndNoStagingFile) {
  const std::string csv = read_file(out() / "fig5-normalization.csv");
  EXPECT_EQ(csv.rfind("n,coef_exact,coef_exact_3dp,coef_paper_fit,delta_paper_fit\n1,", 0), 0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 51);
  EXPECT_NE(csv.find("\n1000,197.498610080195"), std::string::npos);
  for (const auto& entry : fs::directory_iterator(out()))
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(ReportPage, HoldsEverySectionAndFigureWithItsFiles) {
  const auto sections = ids_of(html(), "section");
  for (const char* id : {"claims", "lobes", "normalization", "shader", "differences"}) EXPECT_TRUE(sections.contains(id)) << id;
  const auto figures = ids_of(html(), "figure");
  for (const char* id : {"fig2-lobes", "fig3-relative-error", "fig4-absolute-error", "fig8-pareto-front", "fig9-delta"}) {
    EXPECT_TRUE(figures.contains(id)) << id;
    EXPECT_TRUE(fs::exists(out() / (std::string(id) + ".svg"))) << id;
  }
  for (const char* id : {"fig11-spheres", "differences-n5", "differences-n100"}) {
    EXPECT_TRUE(figures.contains(id)) << id;
    const render::Image png = render::read_png(out() / (std::string(id) + ".png")).image;
    EXPECT_GT(png.width(), png.height()) << id;  // panels side by side
  }
  EXPECT_TRUE(fs::exists(out() / "fig10-log-normalized.glsl"));
  EXPECT_NE(html().find("float specula_log_rv_coef(float n)"), std::string::npos);
  for (const auto& figure : figures) {
    const auto at = html().find(fmt::format("<figure id=\"{}\"", figure));
    const auto end = html().find("</figure>", at);
    EXPECT_NE(html().substr(at, end - at).find("Regenerate: <code>specula "), std::string::npos) << figure;
  }
  for (const char* table : {"fig2-lobes", "fig3-4-errors", "fig5-normalization", "fig8-pareto-front", "fig9-delta"}) {
    EXPECT_TRUE(fs::exists(out() / (std::string(table) + ".csv"))) << table;
    EXPECT_TRUE(nlohmann::json::accept(read_file(out() / (std::string(table) + ".json")))) << table;
  }
}

TEST_F(ReportPage, HasNoExternalReference) {
  const std::regex external(R"((src|href)\s*=\s*["']?\s*(https?:|//|file:)|url\(\s*["']?(https?:|//)|@import|<link\b|<script\b)",
                            std::regex::icase);
  std::smatch match;
  EXPECT_FALSE(std::regex_search(html(), match, external)) << match.str();
  EXPECT_EQ(html().find("http"), std::string::npos);
}

TEST_F(ReportPage, ParsesInChromiumWithTheSameSectionsAndFigures) {
  const Command dom = run(chromium(scratch() / "profile-dom", fmt::format("--dump-dom 'file://{}'", (out() / "index.html").string())));
  ASSERT_EQ(dom.exit_code, 0) << dom.err;
  EXPECT_EQ(ids_of(dom.out, "section"), ids_of(html(), "section"));
  EXPECT_EQ(ids_of(dom.out, "figure"), ids_of(html(), "figure"));
  EXPECT_NE(dom.out.find("<footer>"), std::string::npos);  // nothing swallowed by a broken tag
}

TEST_F(ReportPage, ScreenshotIsNotBlank) {
  const fs::path shot = scratch() / "page.png";
  const Command r = run(chromium(scratch() / "profile-shot", fmt::format("--window-size=1200,2400 --screenshot='{}' 'file://{}'",
                                                                    shot.string(), (out() / "index.html").string())));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const render::Image image = render::read_png(shot).image;
  EXPECT_EQ(image.width(), 1200);
  int ink = 0, coloured = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const render::Rgb c = image.at(x, y);
      ink += c.r + c.g + c.b < 1.5;
      coloured += std::abs(c.r - c.b) > 0.2;  // the model colours of the plots
    }
  const double pixels = static_cast<double>(image.width()) * image.height();
  EXPECT_GT(ink / pixels, 0.01) << "text and axes";
  EXPECT_GT(coloured / pixels, 0.0005) << "coloured plot lines";
}

/// The analysis command's JSON rows.
nlohmann::json command_rows(const std::string& arguments) {
  const Command r = run(fmt::format("'{}' {} --format json", SPECULA_CLI, arguments));
  EXPECT_EQ(r.exit_code, 0) << r.out;
  return nlohmann::json::parse(r.out)["rows"];
}

std::string claims_table(const std::string& html) {
  const auto at = html.find("<table class=\"claims\"");
  return html.substr(at, html.find("</table>", at) - at);
}

TEST_F(ReportPage, ClaimsQuoteWhatTheAnalysisCommandsCompute) {
  const std::string claims = claims_table(html());
  const auto log = command_rows("error --model log --reference phong --n 1,1000");
  EXPECT_NE(claims.find(fmt::format("{:.10g} to {:.10g} for n", log[0]["max_abs"].get<double>(),
                                    log[1]["max_abs"].get<double>())),
            std::string::npos)
      << claims;
  const auto schlick = command_rows("error --model schlick --reference phong --n 2,1000");
  EXPECT_NE(claims.find(fmt::format("Schlick {:.3g} % to {:.3g} %", 100 * schlick[0]["max_rel_epicenter"].get<double>(),
                                    100 * schlick[1]["max_rel_epicenter"].get<double>())),
            std::string::npos)
      << claims;
  EXPECT_NE(claims.find("7/7 printed values"), std::string::npos);
  const auto coef = command_rows("normalize --model log --n 1:7 --round 3");
  for (const auto& row : coef)
    EXPECT_NE(html().find(fmt::format("<td>{:.3f}</td><td>{:.3f}</td>", row["coef"].get<double>(), row["coef"].get<double>())),
              std::string::npos)
        << row;
}

}  // namespace
}  // namespace specula::report
