#pragma once
// Running the specula CLI from a test: exit code, stdout and stderr of one command line.
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <string>

#include "render_support.h"
#include "text_support.h"

namespace specula::testing {

struct CliRun {
  int exit_code;
  std::string out, err;
};

/// `specula` with `arguments` (shell words, quoted by the caller where needed); its output goes
/// to files beside `dir`, so that `dir` holds only what the command wrote.
inline CliRun run_specula(const TempDir& dir, const std::string& arguments) {
  const auto out = dir.path().parent_path() / (dir.path().filename().string() + ".out");
  const auto err = dir.path().parent_path() / (dir.path().filename().string() + ".err");
  const int status = std::system(
      fmt::format("'{}' {} >'{}' 2>'{}'", SPECULA_CLI, arguments, out.string(), err.string()).c_str());
  CliRun run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(out), read_file(err)};
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return run;
}

}  // namespace specula::testing
