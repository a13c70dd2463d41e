// `specula walk` as a user runs it: the table of the library's walk (walk_test.cpp proves the walk
// itself), `specula verdict`, bad input in one line with exit 2, and Ctrl-C.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <thread>

#include "cli/cli_fixture.h"
#include "specula/catalogue/fresnel_spec.h"
#include "specula/exceptions.h"
#include "specula/walk/walk.h"
#include "text_support.h"

namespace specula::testing {
namespace {

using ::testing::HasSubstr;

TEST_F(Cli, WalkPrintsTheLibrarysAlbedoByOrderWithErrors) {
  const Result r = ok({"walk", "--alpha", "0.8", "--theta", "30", "-f", "one", "-f", "schlick:f0=0.04", "--paths", "32768"});
  const auto lines = lines_of(r.out);
  ASSERT_EQ(lines.size(), 3u) << r;
  EXPECT_EQ(lines[0],
            "alpha,theta,mu,channel,order1,order1_se,order2,order2_se,order3,order3_se,order4plus,order4plus_se,total,"
            "total_se,multiple,multiple_se");
  const std::vector<fresnel::Channel> channels{fresnel::Channel{}, parse_fresnel("schlick:f0=0.04")};
  walk::Options options;
  options.paths = 32768;
  const auto expected = walk::conductor_albedo({walk::Distribution::ggx, 0.8}, channels, std::cos(30 * std::numbers::pi / 180), options);
  for (std::size_t c = 0; c < 2; ++c) {
    const auto cells = cells_of(lines[c + 1]);
    ASSERT_EQ(cells.size(), 16u);
    EXPECT_EQ(std::stod(cells[3]), double(c));
    EXPECT_DOUBLE_EQ(std::stod(cells[4]), expected[c].order[0].value);
    EXPECT_DOUBLE_EQ(std::stod(cells[12]), expected[c].total.value);
    EXPECT_DOUBLE_EQ(std::stod(cells[15]), expected[c].multiple.error);
  }
}

TEST_F(Cli, WalkOfADielectricPrintsReflectionTransmissionAndTheirSum) {
  const Result r = ok({"walk", "--alpha", "0.4", "--theta", "70", "--dielectric", "1.5", "--paths", "32768", "--format", "json"});
  EXPECT_THAT(r.out, HasSubstr("\"surface\": \"dielectric interface, eta = 1.5\""));
  EXPECT_THAT(r.out, HasSubstr("\"channel 1\": \"transmission\""));
  walk::Options options;
  options.paths = 32768;
  const auto d = walk::dielectric_albedo({walk::Distribution::ggx, 0.4}, 1.5, std::cos(70 * std::numbers::pi / 180), options);
  EXPECT_THAT(r.out, HasSubstr(fmt::format("\"total\": {}", d.transmission.total.value)));
  EXPECT_THAT(r.out, HasSubstr(fmt::format("\"total\": {}", d.energy.total.value)));
}

TEST_F(Cli, VerdictPrintsEveryCompensationsErrorPerFamily) {
  const Result r = ok({"verdict", "--alpha", "0.5", "--mu", "0.5", "--paths", "32768", "-q", "--format", "json"});
  EXPECT_THAT(r.out, HasSubstr("\"compensation 6\": \"walk-fit\""));
  EXPECT_THAT(r.out, HasSubstr("\"family 4\": \"aluminium\""));
  const Result cells = ok({"verdict", "--alpha", "0.5", "--mu", "0.5", "--paths", "32768", "-q", "--cells"});
  EXPECT_EQ(lines_of(cells.out).size(), 1u + 16);  // the header, one row per Fresnel channel
  EXPECT_THAT(bad({"verdict", "--alpha", "2"}).err, HasSubstr("--alpha"));
  EXPECT_THAT(bad({"verdict", "--mu", "0"}).err, HasSubstr("--mu"));
  EXPECT_THAT(bad({"verdict", "--paths", "10"}).err, HasSubstr("--paths"));
}

TEST_F(Cli, WalkRefusesBadInputInOneLine) {
  EXPECT_THAT(bad({"walk", "-f", "schlick:f0=2"}).err, HasSubstr("f0"));
  EXPECT_THAT(bad({"walk", "-f", "dielectric:eta=-1"}).err, HasSubstr("eta"));
  EXPECT_THAT(bad({"walk", "-f", "conductor:eta=1,kappa=-0.5"}).err, HasSubstr("kappa"));
  EXPECT_THAT(bad({"walk", "--alpha", "0"}).err, HasSubstr("alpha"));
  EXPECT_THAT(bad({"walk", "--theta", "90"}).err, HasSubstr("90"));
  EXPECT_THAT(bad({"walk", "--paths", "68719476737"}).err, HasSubstr("--paths"));
  EXPECT_THAT(bad({"walk", "--paths", "100"}).err, HasSubstr("--paths"));
  EXPECT_THAT(bad({"walk", "--alpha", "0.1:4@200", "--paths", "1000000000"}).err, HasSubstr("paths in all"));
  EXPECT_THAT(bad({"walk", "--outgoing", "95,0"}).err, HasSubstr("--outgoing"));
  EXPECT_THAT(bad({"walk", "--distribution", "phong"}).err, HasSubstr("phong"));
  EXPECT_THAT(bad({"walk", "--dielectric", "0"}).err, HasSubstr("eta"));
  EXPECT_THAT(bad({"walk", "--dielectric", "1.5", "-f", "one"}).err, HasSubstr("--dielectric"));
  EXPECT_TRUE(listing(work()).empty());
}

TEST_F(Cli, WalkStopsAtOnceOnCtrlCWritingNothing) {
  const auto out = work() / "walk.csv";
  const pid_t pid = start({"walk", "--alpha", "1", "--theta", "0", "--paths", "4000000000", "-q", "--out", out.string()});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ::kill(pid, SIGINT);
  const Result r = finish_within(pid, std::chrono::seconds(30));
  EXPECT_EQ(r.code, 128 + SIGINT) << r;
  EXPECT_EQ(r.err, fmt::format("specula: stopped: interrupted by signal {}\n", SIGINT));
  EXPECT_TRUE(listing(work()).empty());
}

}  // namespace
}  // namespace specula::testing
