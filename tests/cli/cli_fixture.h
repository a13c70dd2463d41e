#pragma once
// The CLI test fixture: runs `specula` as a program (no shell) in a fresh directory, capturing
// stdout, stderr and the exit code, with the expectations of a good and of a bad run.
#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <optional>
#include <thread>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "text_support.h"

extern char** environ;

namespace specula::testing {

namespace fs = std::filesystem;
using ::testing::IsEmpty;

inline std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.insert(entry.path().filename().string());
  return names;
}

struct Result {
  int code = -1;
  std::string out;
  std::string err;
};

inline std::ostream& operator<<(std::ostream& os, const Result& r) {
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
  Result run(const std::vector<std::string>& args) { return finish(start(args)); }

  /// Starts `specula args…` (no shell) with stdout and stderr captured; finish() waits for it.
  pid_t start(const std::vector<std::string>& args) {
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
    if (spawned != 0) {
      ADD_FAILURE() << "cannot run " << SPECULA_CLI << ": " << std::strerror(spawned);
      return -1;
    }
    return pid;
  }

  /// finish(), but a command still running after `limit` is killed and fails the test.
  Result finish_within(pid_t pid, std::chrono::seconds limit) {
    const auto give_up = std::chrono::steady_clock::now() + limit;
    int status = 0;
    while (pid > 0 && ::waitpid(pid, &status, WNOHANG) == 0) {
      if (std::chrono::steady_clock::now() > give_up) {
        ADD_FAILURE() << "still running after " << limit.count() << " s: killed";
        ::kill(pid, SIGKILL);
        ::waitpid(pid, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return finish(pid, status);
  }

  /// Waits for a command start() began; its exit code is 128 + the signal when one ended it.
  Result finish(pid_t pid, std::optional<int> reaped_status = std::nullopt) {
    Result r;
    if (pid < 0) return r;
    const fs::path out = dir_ / "capture" / "stdout";
    const fs::path err = dir_ / "capture" / "stderr";
    int status = reaped_status.value_or(0);
    while (!reaped_status && ::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    r.out = specula::testing::read_file(out);
    r.err = specula::testing::read_file(err);
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

}  // namespace specula::testing
