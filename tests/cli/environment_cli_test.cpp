// specula render --env: the white furnace and a probe file through the CLI, the metadata that says
// so, and bad input (one line, exit 2, no file); Ctrl-C stops a long environment render.
#include <csignal>
#include <thread>

#include "cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using specula::testing::Cli;
using specula::testing::listing;
using specula::testing::Result;

TEST_F(Cli, RenderEnvWhiteWritesTheFurnaceImage) {
  const fs::path out = work() / "f.exr";
  ok({"render", "--model", "ggx", "--env", "white", "--size", "16x16", "--samples", "4", "--seed", "3", "-o",
      out.string()});
  EXPECT_TRUE(fs::exists(out));
}

TEST_F(Cli, RenderEnvRefusesBadInput) {
  const std::string out = (work() / "f.exr").string();
  const std::vector<std::string> base{"render", "--model", "ggx", "--size", "8x8", "-o", out};
  const auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  EXPECT_THAT(bad(with({"--env", "white", "--samples", "0"})).err, HasSubstr("--samples 0 is outside [1, 65536]"));
  EXPECT_THAT(bad(with({"--env", (work() / "missing.exr").string()})).err, HasSubstr("cannot read"));
  EXPECT_THAT(bad(with({"--env", "white", "--light", "dir:0,0,1"})).err, HasSubstr("--light cannot be combined"));
  EXPECT_THAT(bad(with({"--env", "white", "--backend", "gl"})).err, HasSubstr("cpu backend only"));
  EXPECT_THAT(bad(with({"--samples", "4"})).err, HasSubstr("--samples requires --env"));
  EXPECT_THAT(listing(work()), IsEmpty());
  ok(with({"--env", "white", "--samples", "1"}));  // control: the same command line, good values
}

TEST_F(Cli, SigintStopsAnEnvironmentRenderWithNoFile) {
  const pid_t pid = start({"render", "--model", "ggx", "--env", "white", "--size", "1024x1024", "--samples", "64",
                           "-o", (work() / "f.exr").string()});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ::kill(pid, SIGINT);
  const Result r = finish(pid);
  EXPECT_EQ(r.code, 128 + SIGINT) << r;
  EXPECT_THAT(listing(work()), IsEmpty());
}

}  // namespace
