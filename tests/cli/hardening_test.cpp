// The CLI against a hostile user: budgets that stop a search, option ranges that bound time and
// memory, inputs with a size cap, outputs that never replace a special file and that no signal or
// kill leaves half-written, and errors that are always one line.
#include <chrono>
#include <csignal>
#include <fstream>
#include <sys/stat.h>
#include <thread>

#include "cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using specula::testing::Cli;
using specula::testing::listing;
using specula::testing::Result;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// ---- fit: every budget honoured -------------------------------------------------------------

TEST_F(Cli, FitWithAFormulaSpaceSmallerThanThePopulationStopsAtItsTimeBudget) {
  const fs::path data = work() / "d.csv";
  write_text(data, "n,coef\n1,0.48\n2,0.66\n3,0.85\n");
  const auto began = Clock::now();
  const pid_t pid = start({"fit", "--data", data.string(), "--target", "coef", "--max-size", "1", "--time", "2", "-q"});
  const Result r = finish_within(pid, std::chrono::seconds(60));
  EXPECT_EQ(r.code, 0) << r;
  EXPECT_THAT(r.out, HasSubstr("stopped by time"));
  EXPECT_LT(seconds_since(began), 30);
}

TEST_F(Cli, FitOptionsBeyondTheirRangeAreUsageErrors) {
  const fs::path data = work() / "d.csv";
  write_text(data, "n,coef\n1,0.48\n2,0.66\n3,0.85\n");
  const std::vector<std::string> base{"fit", "--data", data.string(), "--target", "coef", "-q", "--time", "1"};
  const auto with = [&](std::vector<std::string> extra) {
    auto args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  EXPECT_THAT(bad(with({"--islands", "2147483647"})).err, HasSubstr("--islands"));
  EXPECT_THAT(bad(with({"--population", "1000000"})).err, HasSubstr("--population"));
  EXPECT_THAT(bad(with({"--enumerate-size", "2147483647"})).err, HasSubstr("--enumerate-size"));
  EXPECT_THAT(bad(with({"--max-size", "1000"})).err, HasSubstr("--max-size"));
  EXPECT_THAT(bad(with({"--threads", "100000"})).err, HasSubstr("--threads"));
  // The control: the same command inside the ranges runs.
  EXPECT_EQ(run(with({"--islands", "2", "--population", "20", "--enumerate-size", "3"})).code, 0);
}

TEST_F(Cli, FitRefusesAnEndlessDataFile) {
  const auto began = Clock::now();
  EXPECT_THAT(bad({"fit", "--data", "/dev/zero", "--target", "coef", "-q"}).err, HasSubstr("larger than"));
  EXPECT_LT(seconds_since(began), 60);
}

// ---- lists and counts with a documented range ---------------------------------------------------

TEST_F(Cli, ListsLongerThanTheCommandsCapAreRefused) {
  EXPECT_THAT(bad({"check", "--model", "log-normalized", "--n", "1:1e7"}).err, HasSubstr("--n"));
  EXPECT_THAT(bad({"error", "--model", "log", "--n", "1:1e7"}).err, HasSubstr("--n"));
  EXPECT_THAT(bad({"normalize", "--model", "log", "--n", "1:1e7"}).err, HasSubstr("--n"));
  EXPECT_THAT(bad({"check", "--model", "phong", "--pairs", "100000000"}).err, HasSubstr("--pairs"));
  // The control: a list inside the cap is computed.
  EXPECT_EQ(run({"error", "--model", "log", "--n", "1:3"}).code, 0);
}

// ---- errors are one line ------------------------------------------------------------------------

TEST_F(Cli, AnArgumentHoldingANewlineIsEscapedInTheError) {
  const Result r = bad({"eval", "--model", "log", "--cos", "1", "--coef", "1\n2"});
  EXPECT_THAT(r.err, HasSubstr("1\\n2"));
  EXPECT_THAT(bad({"eval", "--model", "lo\ng", "--cos", "1"}).err, HasSubstr("lo\\ng"));
  EXPECT_THAT(bad({"eval", "--model", "log", "--cos", "1\r\x1b[2J"}).err, HasSubstr("\\r\\x1b[2J"));
}

// ---- outputs --------------------------------------------------------------------------------------

TEST_F(Cli, OutToACharacterDeviceWritesIntoIt) {
  ok({"eval", "--model", "log", "--cos", "1", "-o", "/dev/null"});
  struct stat info {};
  ASSERT_EQ(::stat("/dev/null", &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));
}

TEST_F(Cli, OutToAFifoWritesIntoIt) {
  const fs::path fifo = work() / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = specula::testing::read_file(fifo); });
  ok({"eval", "--model", "log", "--cos", "1", "-o", fifo.string()});
  reader.join();
  EXPECT_THAT(received, HasSubstr("cos,value\n1,"));
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST_F(Cli, OutThroughASymlinkWritesItsTargetAndKeepsTheLink) {
  const fs::path target = work() / "target.csv", link = work() / "link.csv";
  write_text(target, "old\n");
  fs::create_symlink(target, link);
  ok({"eval", "--model", "log", "--cos", "1", "-o", link.string()});
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_THAT(specula::testing::read_file(target), HasSubstr("cos,value"));
  EXPECT_THAT(listing(work()), ElementsAre("link.csv", "target.csv"));
}

TEST_F(Cli, AnOutputNameOfTheMaximumLengthWorks) {
  const std::string name(254, 'e');
  ok({"eval", "--model", "log", "--cos", "1", "-o", (work() / name).string()});
  EXPECT_THAT(listing(work()), ElementsAre(name));
}

/// c op c op … c, at most `characters` long.
std::string chain(const std::string& op, std::size_t characters) {
  std::string text = "c";
  while (text.size() + op.size() + 1 <= characters) text += op + "c";
  return text;
}

/// A lobe of some 2000 operations per evaluation: the commands below outlast their 1.5 s before
/// the signal by construction, in any build (a release `eval` of `log` at 3·10⁶ values, or a
/// 3000² GGX render with one light, finished first on an idle machine).
std::string costly_lobe() { return "lobe: " + chain("*", 4000); }

// SIGKILL in the middle of a large write: nothing is left, under any name.
TEST_F(Cli, AKilledEvalLeavesNoFile) {
  const pid_t pid = start({"eval", "--model", costly_lobe(), "--cos", "0:1@3000000", "-o", (work() / "e.csv").string()});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ::kill(pid, SIGKILL);
  const Result r = finish(pid);
  ASSERT_EQ(r.code, 128 + SIGKILL) << "the command ended before the kill; the test proves nothing";
  EXPECT_THAT(listing(work()), IsEmpty());
}

TEST_F(Cli, SigintAndSigtermStopARenderWithTheirExitCodesAndNoFile) {
  for (const int signal : {SIGINT, SIGTERM}) {
    std::vector<std::string> args{"render", "--model", costly_lobe(), "--size", "3000x3000", "-o", (work() / "y.exr").string()};
    for (int light = 0; light < 16; ++light) args.insert(args.end(), {"--light", "dir:-1,1,1"});  // 1.5 s each
    const pid_t pid = start(args);
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    ::kill(pid, signal);
    const auto stopped = Clock::now();
    const Result r = finish(pid);
    EXPECT_EQ(r.code, 128 + signal) << r;
    EXPECT_LT(seconds_since(stopped), 5);
    EXPECT_THAT(listing(work()), IsEmpty());
  }
}

// A user model checks the stop flag while it is made (the kink search) and inside each integral
// (issue 23): the work itself stops ("interrupted by signal 2"), not StopSignals' forced exit
// after its 2 s grace ("specula: stopped" alone, also 130: what these did before).

TEST_F(Cli, SigintStopsTheWorkOfAUserModelItself) {
  // 584 nested max(): seconds of kink search per model made.
  std::string nested = "max(0, sin(1000*acos(";
  for (int i = 0; i < 500; ++i) nested += "max(";
  nested += "c";
  for (int i = 0; i < 500; ++i) nested += ",c)";
  nested += ")))";
  // Two lets of 4091 characters: the albedo at 40° is one integral of seconds.
  const fs::path file = work() / "costly.toml";
  write_text(file, fmt::format("[[model]]\nid = \"costly\"\nname = \"costly\"\nkind = \"lobe\"\nform = \"rv\"\n"
                               "let = [\"a = {0}\", \"b = {0}\"]\n"
                               "lobe = \"max(0, sin(1000*acos(c))) + 0*(a + b)\"\nnormalization = \"none\"\n",
                               chain("+", 4091)));
  // The nested lobe's albedos: making the model is quick since it is made once (issue 24); forty
  // integrals of an oscillation through 500 nested max() take some 40 s.
  const std::vector<std::string> commands[] = {{"albedo", "--model", "lobe: " + nested, "--theta", "0:78@40"},
                                               {"albedo", "--models", file.string(), "--model", "costly", "--theta", "40"}};
  for (const auto& command : commands) {
    const pid_t pid = start(command);
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    ::kill(pid, SIGINT);
    const auto stopped = Clock::now();
    const Result r = finish_within(pid, std::chrono::seconds(60));
    EXPECT_EQ(r.code, 128 + SIGINT) << command[0] << "\n" << r;
    EXPECT_EQ(r.err, fmt::format("specula: stopped: interrupted by signal {}\n", SIGINT)) << command[0];
    EXPECT_LT(seconds_since(stopped), 5) << command[0];
  }
}

}  // namespace

// ---- design: --out never replaces what specula did not write; integers are strict -------------

TEST_F(Cli, DesignRefusesAnOutHoldingOtherFilesBeforeAnyWorkAndKeepsAUsersFile) {
  const fs::path user = work() / "user";
  fs::create_directory(user);
  std::ofstream(user / "thesis.tex") << "years of work\n";
  const std::vector<std::string> tiny{"design", "-q", "--no-timing", "--max-cost", "1", "--ops", "fma,max", "--range", "n=1:10"};
  const auto with_out = [&](const std::string& out) {
    auto args = tiny;
    args.insert(args.end(), {"--out", out});
    return args;
  };
  for (const std::string& out : {user.string(), user.string() + "/", (user / ".").string(), (user / "x" / "..").string()})
    EXPECT_THAT(bad(with_out(out)).err, HasSubstr("not an earlier output of `specula design`")) << out;
  EXPECT_THAT(bad(with_out(fs::current_path().string())).err, HasSubstr("working directory"));  // specula's, as the test's
  EXPECT_THAT(bad(with_out(".")).err, HasSubstr("working directory"));
  EXPECT_EQ(specula::testing::read_file(user / "thesis.tex"), "years of work\n");
  // The controls: a new directory given with a final '/', and a user's file in it kept by the next run.
  EXPECT_EQ(run(with_out((work() / "front").string() + "/")).code, 0);
  EXPECT_TRUE(fs::exists(work() / "front" / "design.json"));
  std::ofstream(work() / "front" / "notes.txt") << "mine\n";
  EXPECT_EQ(run(with_out((work() / "front").string())).code, 0);
  EXPECT_EQ(specula::testing::read_file(work() / "front" / "notes.txt"), "mine\n");
}

TEST_F(Cli, IntegerOptionsTakeDecimalDigitsOnly) {
  const std::vector<std::vector<std::string>> refused{
      {"--seed", "-1"}, {"--seed", "18446744073709551616"}, {"--seed", ""}, {"--max-cost", "0x2"},
      {"--max-cost", " 2"}, {"--max-cost", "+2"}, {"--shard", "+0/4"}, {"--shard", "0/4 "}, {"--threads", "1e1"}};
  for (const auto& option : refused) {
    std::vector<std::string> args{"design", "-q", "--no-timing", "--out", (work() / "d").string()};
    args.insert(args.end(), option.begin(), option.end());
    const Result r = bad(args);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr(option[0])) << r.err;
  }
  EXPECT_THAT(bad({"eval", "-m", "log", "--cos", "1", "--round", "0x3"}).err, HasSubstr("--round"));  // every command
  EXPECT_EQ(run({"eval", "-m", "log", "--cos", "1", "--round", "3"}).code, 0);  // the control
  EXPECT_FALSE(fs::exists(work() / "d"));
}

// ---- design: bad settings are refused before any work, and nothing is written ------------------

TEST_F(Cli, DesignRefusesBadSettingsInOneLineWritingNothing) {
  const fs::path out = work() / "front";
  const std::vector<std::string> base{"design", "--out", out.string(), "-q", "--no-timing"};
  const auto with = [&](std::vector<std::string> extra) {
    auto args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  };
  EXPECT_THAT(bad(with({"--target", "ggx"})).err, HasSubstr("not a lobe"));
  EXPECT_THAT(bad(with({"--target", "nosuch"})).err, HasSubstr("nosuch"));
  EXPECT_THAT(bad(with({"--range", "n=0:10"})).err, HasSubstr("outside"));
  EXPECT_THAT(bad(with({"--range", "n=10:1"})).err, HasSubstr("empty"));
  EXPECT_THAT(bad(with({"--range", "n10"})).err, HasSubstr("NAME=LO:HI"));
  EXPECT_THAT(bad(with({"--range", "s=1:10"})).err, HasSubstr("no parameter 's'"));
  EXPECT_THAT(bad(with({"--shard", "3/2"})).err, HasSubstr("shard"));
  EXPECT_THAT(bad(with({"--shard", "1-2"})).err, HasSubstr("I/N"));
  EXPECT_THAT(bad(with({"--max-cost", "99"})).err, HasSubstr("--max-cost"));
  EXPECT_THAT(bad(with({"--max-forms", "0"})).err, HasSubstr("--max-forms"));
  EXPECT_THAT(bad(with({"--time", "-1"})).err, HasSubstr("time"));
  EXPECT_THAT(bad(with({"--ops", "fma,tan"})).err, HasSubstr("unknown operation 'tan'"));
  EXPECT_THAT(bad(with({"--objective", "median"})).err, HasSubstr("--objective"));
  EXPECT_THAT(bad(with({"--precision", "quad"})).err, HasSubstr("--precision"));
  EXPECT_THAT(bad({"design", "--out", "/proc/version/x", "-q", "--max-cost", "1", "--no-timing"}).err,
              HasSubstr("cannot"));
  EXPECT_FALSE(fs::exists(out));
  // The control: the same command inside the ranges writes the front (cost 1, one shape: 2 s under
  // the sanitizers, where cost 2's law member took 10 s).
  EXPECT_EQ(run(with({"--range", "n=1:10", "--ops", "fma,max", "--max-cost", "1"})).code, 0);
  EXPECT_TRUE(fs::exists(out / "front.csv"));
  EXPECT_TRUE(fs::exists(out / "models.toml"));
}

// ---- design: a function target's front is written with its page --------------------------------

// The page of a function target plots |F − target| against its first variable, the largest over
// the others, and shows each member's GLSL function (a function is not a lobe: no lobe model is
// made of it). Cost 1, no timing: about 8 s under the sanitizers (the two-variable measurement).
TEST_F(Cli, DesignWritesTheFrontAndPageOfFunctionTargets) {
  for (const std::string target : {"smith-g2-ggx", "schlick-weight"}) {
    const fs::path out = work() / target;
    const Result r = run({"design", "--target", target, "--max-cost", "1", "-q", "--no-timing", "--out", out.string()});
    ASSERT_EQ(r.code, 0) << r;
    const std::string page = specula::testing::read_file(out / "index.html");
    EXPECT_THAT(page, HasSubstr("float specula_term(")) << target;
    EXPECT_THAT(page, HasSubstr(target == "smith-g2-ggx" ? "against NoV (the largest over the other variables)" : "against c"));
  }
}
