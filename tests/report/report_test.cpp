// The report: writes a self-contained page with the paper's Fig. 5 and its table as CSV.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "specula/error.h"
#include "specula/report/report.h"
#include "text_support.h"

namespace specula::report {
namespace {

using specula::testing::read_file;

class ReportTest : public ::testing::Test {
 protected:
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("specula-report-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
                               "-" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(ReportTest, WritesFig5WithThePapersRowsMatched) {
  std::vector<std::string> sections;
  write_report({dir, true, [&](std::string_view s) { sections.emplace_back(s); }});
  EXPECT_FALSE(sections.empty());
  const std::string html = read_file(dir / "index.html");
  EXPECT_NE(html.find("Fig. 5"), std::string::npos);
  EXPECT_NE(html.find("<td>0.483</td><td>0.483</td>"), std::string::npos);
  EXPECT_NE(html.find("<td>1.634</td><td>1.634</td>"), std::string::npos);
  EXPECT_EQ(html.find("differs"), std::string::npos);
  EXPECT_EQ(html.find("http://"), std::string::npos);   // self-contained: no external references
  EXPECT_EQ(html.find("https://"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);

  const std::string csv = read_file(dir / "fig5-normalization.csv");
  EXPECT_EQ(csv.rfind("n,coef_exact,coef_exact_3dp,coef_paper_fit,delta_paper_fit\n1,", 0), 0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 51);
  EXPECT_NE(csv.find("\n1000,197.498610080195"), std::string::npos);
}

TEST_F(ReportTest, RefusesAnOutputThatIsAFile) {
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "file") << "x";
  EXPECT_THROW(write_report({dir / "file"}), InvalidArgument);
}

}  // namespace
}  // namespace specula::report
