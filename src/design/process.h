#pragma once
// Running a tool (the compiler, glslangValidator) as a child process, bounded in time and
// stoppable: what the designer measures with.
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace specula::design {

/// Runs argv (argv[0] looked up in PATH) with stdout and stderr to `log`; its exit status (128
/// for a signal). Throws std::runtime_error if it cannot start, runs past `limit` (killed), or
/// `stop` says so meanwhile (killed).
int run_process(const std::vector<std::string>& argv, const std::filesystem::path& log,
                const std::function<bool()>& stop, std::chrono::seconds limit);

/// The first line of `log` that mentions an error, else "no message".
std::string first_error(const std::filesystem::path& log);

}  // namespace specula::design
