// `specula sample` and `specula check --sampling` as a user runs them.
#include <cmath>
#include <numbers>
#include <sstream>

#include "cli_fixture.h"
#include "specula/catalogue/catalogue.h"
#include "specula/sampling/sampler.h"

namespace specula::testing {
namespace {

std::vector<std::vector<double>> csv_rows(const std::string& text, std::string& header) {
  std::istringstream in(text);
  std::getline(in, header);
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<double> row;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::stod(field));
    rows.push_back(row);
  }
  return rows;
}

int count_substrings(const std::string& text, const std::string& what) {
  int count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

TEST_F(Cli, SampleWritesTheLibrarysSamples) {
  const Result r = ok({"sample", "--model", "ggx", "-p", "alpha=0.2", "--theta-i", "60", "--count", "3000", "--seed", "5"});
  std::string header;
  const auto rows = csv_rows(r.out, header);
  EXPECT_EQ(header, "x,y,z,pdf,weight");
  ASSERT_EQ(rows.size(), 3000u);
  const Model model = make_model("ggx", {{"alpha", 0.2}});
  const sampling::Sampler sampler(model);
  const Vec3 wi{std::sin(std::numbers::pi / 3), 0, std::cos(std::numbers::pi / 3)};
  const auto expected = sampling::draw_samples(sampler, wi, 3000, 5);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 5u);
    EXPECT_EQ(rows[i][0], expected[i].wo.x);
    EXPECT_EQ(rows[i][3], expected[i].pdf);
    EXPECT_EQ(rows[i][4], expected[i].weight);
    if (rows[i][3] > 0) {
      EXPECT_GT(rows[i][2], 0);
      const Vec3 wo{rows[i][0], rows[i][1], rows[i][2]};
      EXPECT_NEAR(rows[i][4], model({0, 0, 1}, wi, wo) * wo.z / rows[i][3], 1e-12 * rows[i][4]);
    }
  }
  EXPECT_NE(ok({"sample", "--model", "ggx", "--count", "3", "--seed", "6"}).out,
            ok({"sample", "--model", "ggx", "--count", "3", "--seed", "5"}).out);
}

TEST_F(Cli, SampleWritesAtomicallyAndRefusesBadInput) {
  ok({"sample", "--model", "log-normalized", "--count", "10", "--out", (work() / "s.csv").string()});
  EXPECT_EQ(listing(work()), std::set<std::string>{"s.csv"});
  bad({"sample", "--model", "ggx", "--theta-i", "90"});
  bad({"sample", "--model", "ggx", "--count", "0"});
  bad({"sample", "--model", "ggx", "--count", "2000000"});
  bad({"sample", "--model", "nope"});
  bad({"sample", "--model", "ggx", "--count", "10", "--out", (work() / "missing" / "s.csv").string()});
  EXPECT_EQ(listing(work()), std::set<std::string>{"s.csv"});
}

TEST_F(Cli, CheckSamplingPassesAndDrawsTheHeatMap) {
  const std::string png = (work() / "chi2.png").string();
  const Result r = ok({"check", "--model", "log-normalized", "-p", "n=50", "--sampling", "--samples", "100000",
                       "--theta-i", "0,45,85", "--out", png});
  EXPECT_THAT(r.out, ::testing::HasSubstr("log lobe in t-space"));
  EXPECT_EQ(count_substrings(r.out, "passes"), 3) << r.out;
  EXPECT_TRUE(fs::exists(png));
  const Result json = ok({"check", "--model", "lambert", "--sampling", "--samples", "10000", "--json"});
  EXPECT_THAT(json.out, ::testing::HasSubstr("\"passes\": true"));
}

// Issue 23: a negative model ran `check --sampling` past 25 s; it is the check's finding, printed
// at once (exit 1), and no further angle is checked. `brdf: nl` is the control.
TEST_F(Cli, CheckSamplingOfANegativeModelSaysSoAndStops) {
  const std::string png = (work() / "negative.png").string();
  const Result r = finish_within(start({"check", "--model", "brdf: -nl", "--sampling", "--samples", "1000", "--theta-i",
                                        "0,30", "--out", png}),
                                 std::chrono::seconds(60));
  EXPECT_EQ(r.code, 1) << r;
  EXPECT_THAT(r.out, ::testing::HasSubstr(
                         "0° FAILS: f < 0 at 1000 samples (min f = -1): the model is negative; the check stops here\n"));
  EXPECT_EQ(r.out.find("30°"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
  EXPECT_TRUE(fs::exists(png));
  const Result json = run({"check", "--model", "brdf: -nl", "--sampling", "--samples", "1000", "--json"});
  EXPECT_EQ(json.code, 1);
  EXPECT_THAT(json.out, ::testing::HasSubstr("\"negative\": 1000, \"min_f\": -1, \"non_finite\": 0, \"passes\": false"));
  const Result control = ok({"check", "--model", "brdf: nl", "--sampling", "--samples", "1000", "--theta-i", "0,30"});
  EXPECT_EQ(count_substrings(control.out, "passes"), 2) << control.out;
  EXPECT_EQ(control.out.find("f < 0"), std::string::npos);
}

// So is a model that is inf or NaN, in text and JSON (null for the numbers JSON has none for).
TEST_F(Cli, CheckSamplingOfANonFiniteModelSaysSoAndStops) {
  const Result r = finish_within(start({"check", "--model", "brdf: sqrt(-nl)", "--sampling", "--samples", "1000",
                                        "--theta-i", "0,30"}),
                                 std::chrono::seconds(60));
  EXPECT_EQ(r.code, 1) << r;
  EXPECT_THAT(r.out, ::testing::HasSubstr(
                         "0° FAILS: f is inf or NaN at 1000 samples: the model is not finite; the check stops here\n"));
  EXPECT_EQ(r.out.find("30°"), std::string::npos) << r.out;
  const Result json = finish_within(start({"check", "--model", "brdf: 1e308", "--sampling", "--samples", "1000",
                                           "--theta-i", "0", "--json"}),
                                    std::chrono::seconds(60));
  EXPECT_EQ(json.code, 1) << json;
  EXPECT_THAT(json.out, ::testing::HasSubstr("\"albedo\": null"));
  EXPECT_THAT(json.out, ::testing::HasSubstr("\"non_finite\": 0, \"passes\": false"));
}

TEST_F(Cli, CheckSamplingRefusesBadInput) {
  bad({"check", "--model", "ggx", "--sampling", "--theta-i", "95"});
  bad({"check", "--model", "ggx", "--sampling", "--samples", "10"});
  bad({"check", "--model", "ggx", "--sampling", "--bins", "1000"});
  bad({"check", "--model", "ggx", "--sampling", "--n", "1,2"});
  bad({"check", "--model", "ggx", "--sampling", "--theta-i", "0:89@30"});
  // At most 3e7 samples over all angles: refused before any is drawn (at once, not minutes later).
  EXPECT_THAT(bad({"check", "--model", "ggx", "--sampling", "--samples", "100000000", "--theta-i", "0"}).err,
              ::testing::HasSubstr("--samples"));
  EXPECT_THAT(bad({"check", "--model", "ggx", "--sampling", "--samples", "20000000", "--theta-i", "0,30,60"}).err,
              ::testing::HasSubstr("60000000 samples, more than the 30000000"));
}

}  // namespace
}  // namespace specula::testing
