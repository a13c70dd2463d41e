#pragma once
// Running a tool (the compiler, glslangValidator) as a child process, bounded in time and
// stoppable, and the scratch directories it works in: what the designer measures with.
//
// A tool never outlives the run that started it. It runs under a small keeper process of its
// own (a fork of specula) that leads a process group holding the tool and everything the tool
// starts (the compiler driver's cc1plus, as, ld). A stop, a time-out or any exit of specula
// kills that whole group: the first two from run_process, the last through the keeper's parent-
// death signal, which the kernel sends even when specula is killed by SIGKILL.
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace specula::design {

/// Runs argv (argv[0] a path, or a name looked up in PATH) with stdin from /dev/null and stdout
/// and stderr to `log`; its exit status (128 for a signal). Throws std::runtime_error if it
/// cannot start or runs past `limit`, and Interrupted (specula/interrupt) if `stop` says so
/// meanwhile; either way the tool and its children are killed before the call returns.
int run_process(const std::vector<std::string>& argv, const std::filesystem::path& log,
                const std::function<bool()>& stop, std::chrono::seconds limit);

/// The executable file `name` names: itself if it holds a '/', else the first match in PATH;
/// empty if there is none.
std::filesystem::path find_executable(std::string_view name);

/// The first line of `log` that mentions an error, else "no message".
std::string first_error(const std::filesystem::path& log);

/// A private directory in the system's temporary directory, "specula-design-[TAG-]PID-SERIAL",
/// removed with its contents when destroyed (an error, a stop: every exit that unwinds). Creating
/// one first removes those of processes that have ended (a killed run's, a server's that did not
/// stop in time).
class ScratchDirectory {
 public:
  /// Throws std::runtime_error if it cannot be created.
  explicit ScratchDirectory(std::string_view tag = {});
  ~ScratchDirectory();
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
};

/// The scratch directories' names start with this, in std::filesystem::temp_directory_path().
inline constexpr std::string_view kScratchPrefix = "specula-design-";

}  // namespace specula::design
