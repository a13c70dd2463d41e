#include "process.h"

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <fstream>
#include <optional>
#include <signal.h>
#include <stdexcept>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "specula/interrupt/interrupt.h"

namespace specula::design {
namespace {

namespace fs = std::filesystem;

// ---- The keeper: a fork of specula, so async-signal-safe calls only. ----------------------

void kill_own_group(int) { ::kill(0, SIGKILL); }

// `from` as descriptor `to`, open across exec.
void redirect(int from, int to) {
  if (from == to) ::fcntl(to, F_SETFD, 0);
  else ::dup2(from, to);
}

// Leads a new process group, runs the tool in it and exits with its status; when specula ends
// first (the parent-death signal), or on SIGINT/SIGHUP, kills the whole group, itself included.
[[noreturn]] void keep(pid_t parent, const char* path, char* const* argv, int input, int log) {
  ::setpgid(0, 0);
  struct sigaction action {};
  action.sa_handler = kill_own_group;
  sigemptyset(&action.sa_mask);
  for (const int sig : {SIGTERM, SIGINT, SIGHUP}) ::sigaction(sig, &action, nullptr);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  ::prctl(PR_SET_PDEATHSIG, SIGTERM);
  if (::getppid() != parent) kill_own_group(0);  // specula ended before the signal was armed
  redirect(input, STDIN_FILENO);
  redirect(log, STDOUT_FILENO);
  redirect(log, STDERR_FILENO);
  ::close_range(3, ~0U, 0);  // no socket or file of specula's held open by the tool
  const pid_t tool = ::fork();
  if (tool == 0) {
    ::execv(path, argv);  // the handlers above are reset by exec; the mask stays empty
    ::_exit(127);
  }
  if (tool < 0) ::_exit(126);
  int status = 0;
  while (::waitpid(tool, &status, 0) < 0)
    if (errno != EINTR) ::_exit(126);
  ::_exit(WIFEXITED(status) ? WEXITSTATUS(status) : 128);
}

// ---- specula's side. --------------------------------------------------------------------

/// A descriptor closed on scope exit.
struct Descriptor {
  int fd;
  explicit Descriptor(int value) : fd(value) {}
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
};

/// The keeper's process group, killed and reaped on scope exit unless it has ended.
class Group {
 public:
  explicit Group(pid_t leader) : leader_(leader) { ::setpgid(leader, leader); }  // also set by the keeper: whichever runs first
  ~Group() {
    if (leader_ <= 0) return;
    ::kill(-leader_, SIGKILL);
    ::kill(leader_, SIGKILL);  // in case it had not yet made its group
    int status = 0;
    while (::waitpid(leader_, &status, 0) < 0 && errno == EINTR) {
    }
  }
  Group(const Group&) = delete;
  Group& operator=(const Group&) = delete;

  /// The keeper's exit status once it has ended.
  std::optional<int> ended() {
    int status = 0;
    if (::waitpid(leader_, &status, WNOHANG) != leader_) return std::nullopt;
    leader_ = 0;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
  }

 private:
  pid_t leader_;
};

bool executable_file(const fs::path& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) && ::access(path.c_str(), X_OK) == 0;
}

/// The owner's process id in a scratch directory's name ("specula-design-[TAG-]PID[-SERIAL]").
std::optional<pid_t> scratch_owner(std::string_view name) {
  if (!name.starts_with(kScratchPrefix)) return std::nullopt;
  name.remove_prefix(kScratchPrefix.size());
  while (!name.empty()) {
    const std::string_view field = name.substr(0, name.find('-'));
    if (!field.empty() && field.size() <= 9 && field.find_first_not_of("0123456789") == std::string_view::npos)
      return static_cast<pid_t>(std::stol(std::string(field)));
    if (field.size() == name.size()) break;
    name.remove_prefix(field.size() + 1);
  }
  return std::nullopt;
}

void remove_stale_scratch(const fs::path& temp) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(temp, ec)) {
    const auto owner = scratch_owner(entry.path().filename().string());
    if (!owner || *owner == ::getpid() || ::kill(*owner, 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    if (entry.symlink_status(ignored).type() == fs::file_type::directory) fs::remove_all(entry.path(), ignored);
  }
}

}  // namespace

fs::path find_executable(std::string_view name) {
  if (name.empty()) return {};
  if (name.find('/') != std::string_view::npos) return executable_file(fs::path(name)) ? fs::path(name) : fs::path();
  const char* path = std::getenv("PATH");
  std::string_view dirs = path && *path ? path : "/usr/local/bin:/usr/bin:/bin";
  while (true) {
    const std::string_view dir = dirs.substr(0, dirs.find(':'));
    const fs::path candidate = fs::path(dir.empty() ? "." : std::string(dir)) / name;
    if (executable_file(candidate)) return candidate;
    if (dir.size() == dirs.size()) return {};
    dirs.remove_prefix(dir.size() + 1);
  }
}

int run_process(const std::vector<std::string>& argv, const fs::path& log, const std::function<bool()>& stop,
                std::chrono::seconds limit) {
  const fs::path program = find_executable(argv.at(0));
  if (program.empty()) throw std::runtime_error(fmt::format("cannot run {}: no such executable file", argv[0]));
  const Descriptor output(::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644));
  const Descriptor input(::open("/dev/null", O_RDONLY | O_CLOEXEC));
  if (output.fd < 0 || input.fd < 0) throw std::runtime_error(fmt::format("cannot run {}: {}", argv[0], std::strerror(errno)));
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const std::string path = program.string();
  const pid_t parent = ::getpid();
  const pid_t keeper = ::fork();
  if (keeper == 0) keep(parent, path.c_str(), args.data(), input.fd, output.fd);
  if (keeper < 0) throw std::runtime_error(fmt::format("cannot run {}: {}", argv[0], std::strerror(errno)));
  Group group(keeper);
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    if (const auto status = group.ended()) {
      if (*status == 127) throw std::runtime_error(fmt::format("cannot run {}: it could not be executed", argv[0]));
      return *status;
    }
    if (stop()) {
      const int signal = stop_requested();
      throw Interrupted(signal != 0 ? Interrupted::Reason::signal : Interrupted::Reason::cancelled, signal);
    }
    if (std::chrono::steady_clock::now() - start > limit)
      throw std::runtime_error(fmt::format("{} took over {} s", argv[0], limit.count()));
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

std::string first_error(const fs::path& log) {
  std::ifstream in(log);
  std::string line;
  while (std::getline(in, line))
    if (line.find("rror") != std::string::npos) return line;
  return "no message";
}

ScratchDirectory::ScratchDirectory(std::string_view tag) {
  static std::atomic<unsigned> serial = 0;
  std::error_code ec;
  const fs::path temp = fs::temp_directory_path(ec);
  if (ec) throw std::runtime_error(fmt::format("no temporary directory: {}", ec.message()));
  remove_stale_scratch(temp);
  const std::string tagged = tag.empty() ? std::string() : fmt::format("{}-", tag);
  path_ = temp / fmt::format("{}{}{}-{}", kScratchPrefix, tagged, ::getpid(), serial++);
  fs::remove_all(path_, ec);
  if (::mkdir(path_.c_str(), 0700) != 0)
    throw std::runtime_error(fmt::format("cannot create {}: {}", path_.string(), std::strerror(errno)));
}

ScratchDirectory::~ScratchDirectory() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

}  // namespace specula::design
