// `specula serve` as a program: it prints its URL, answers, and exits 0 on SIGTERM or SIGINT,
// also with a fit job running; a port in use is a one-line error with exit code 2.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <fmt/format.h>
#include <iostream>
#include <thread>
#include <vector>

#include "serve_support.h"

extern char** environ;

namespace specula::serve {
namespace {

using specula::testing::get;
using specula::testing::post;
using ::testing::HasSubstr;
using ::testing::StartsWith;

/// `specula serve ARGS` with stdout and stderr on pipes.
class ServeProcess {
 public:
  explicit ServeProcess(std::vector<std::string> args) {
    int out[2], err[2];
    if (::pipe(out) != 0 || ::pipe(err) != 0) throw std::runtime_error("pipe");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, out[1], 1);
    posix_spawn_file_actions_adddup2(&actions, err[1], 2);
    posix_spawn_file_actions_addclose(&actions, out[0]);
    posix_spawn_file_actions_addclose(&actions, err[0]);
    args.insert(args.begin(), {SPECULA_CLI, "serve"});
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int spawned = posix_spawn(&pid_, SPECULA_CLI, &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(out[1]);
    ::close(err[1]);
    out_ = out[0];
    err_ = err[0];
    if (spawned != 0) throw std::runtime_error("cannot run " SPECULA_CLI);
  }
  ~ServeProcess() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    ::close(out_);
    ::close(err_);
  }

  /// The first line on stdout (waits up to `seconds`; "" if none).
  std::string first_line(int seconds = 60) {
    std::string line;
    pollfd p{out_, POLLIN, 0};
    char ch = 0;
    while (::poll(&p, 1, seconds * 1000) > 0 && ::read(out_, &ch, 1) == 1 && ch != '\n') line += ch;
    return line;
  }

  /// Everything on stderr until the process closes it.
  std::string all_stderr() {
    std::string text;
    char buffer[1024];
    for (ssize_t got; (got = ::read(err_, buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(got));
    return text;
  }

  void signal(int number) { ::kill(pid_, number); }

  /// The exit code once the process ends (-1 if killed by a signal, -2 if still running after
  /// `seconds`, a bound against hanging, not a timing requirement).
  int exit_code(int seconds = 30) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > deadline) return -2;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    exited_ = true;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

 private:
  pid_t pid_ = 0;
  int out_ = -1, err_ = -1;
  bool exited_ = false;
};

int port_of(const std::string& serving_line) {
  const auto colon = serving_line.rfind(':');
  return colon == std::string::npos ? 0 : std::atoi(serving_line.c_str() + colon + 1);
}

TEST(ServeCli, PrintsItsUrlAnswersAndExitsZeroOnSigterm) {
  ServeProcess serve({"--port", "0"});
  const std::string line = serve.first_line();
  ASSERT_THAT(line, StartsWith("serving http://127.0.0.1:"));
  const int port = port_of(line);
  EXPECT_EQ(get(port, "/api/models").status, 200);
  serve.signal(SIGTERM);
  EXPECT_EQ(serve.exit_code(), 0);
  EXPECT_EQ(serve.all_stderr(), "");
}

TEST(ServeCli, ExitsZeroOnSigintWithAFitJobRunning) {
  ServeProcess serve({"--port", "0"});
  const int port = port_of(serve.first_line());
  ASSERT_GT(port, 0);
  ASSERT_EQ(post(port, "/api/fit", R"({"model": "log", "generations": 100000, "time": 60})").status, 202);
  serve.signal(SIGINT);
  EXPECT_EQ(serve.exit_code(), 0);
}

TEST(ServeCli, ExitsZeroWithinASecondOfSigtermWithRequestsAndAFitInFlight) {
  ServeProcess serve({"--port", "0"});
  const int port = port_of(serve.first_line());
  ASSERT_GT(port, 0);
  std::vector<std::thread> heavy;
  for (int i = 0; i < 3; ++i)
    heavy.emplace_back([port] { post(port, "/api/check", R"({"model": "ggx", "step": 0.01, "pairs": 1})"); });
  specula::testing::RawConnection drip(port);
  ASSERT_TRUE(drip.send("GET /api/mo"));
  ASSERT_EQ(post(port, "/api/fit", R"({"model": "log", "generations": 100000, "time": 60})").status, 202);
  std::this_thread::sleep_for(std::chrono::milliseconds(700));
  const auto start = std::chrono::steady_clock::now();
  serve.signal(SIGTERM);
  EXPECT_EQ(serve.exit_code(), 0);
  const double took = specula::testing::seconds_since(start);
  std::cout << "[ measured ] exited " << took << " s after SIGTERM\n";
  EXPECT_LT(took, 1.0);
  for (auto& t : heavy) t.join();
}

TEST(ServeCli, ExitsZeroOnSigtermWithAFitJobThatDoesNotStop) {
  ServeProcess serve({"--port", "0"});
  const int port = port_of(serve.first_line());
  ASSERT_GT(port, 0);
  // A search of a formula space smaller than its population (serve_jobs_test.cpp): one that may
  // not notice its cancel flag. The server waits Limits::stop_seconds for it, then exits anyway.
  ASSERT_EQ(post(port, "/api/fit", R"({"data": {"columns": {"x": [1, 2, 3, 4], "y": [2, 4, 6, 8]}, "target": "y"},
                                       "ops": "+", "max_size": 1, "time": 2})").status, 202);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const auto start = std::chrono::steady_clock::now();
  serve.signal(SIGTERM);
  EXPECT_EQ(serve.exit_code(), 0);  // not 143, the hard exit of the signal's grace period
  const double took = specula::testing::seconds_since(start);
  std::cout << "[ measured ] exited " << took << " s after SIGTERM\n";
  EXPECT_LT(took, 1.5);
}

TEST(ServeCli, APortInUseIsAnError) {
  ServeProcess first({"--port", "0"});
  const int port = port_of(first.first_line());
  ASSERT_GT(port, 0);
  ServeProcess second({"--port", std::to_string(port)});
  EXPECT_EQ(second.exit_code(), 2);
  EXPECT_THAT(second.all_stderr(), HasSubstr(fmt::format("cannot listen on 127.0.0.1:{}", port)));
  first.signal(SIGTERM);
  EXPECT_EQ(first.exit_code(), 0);
}

}  // namespace
}  // namespace specula::serve
