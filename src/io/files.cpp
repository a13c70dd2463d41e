#include "specula/io/files.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <fcntl.h>
#include <signal.h>
#include <fmt/format.h>
#include <fstream>
#include <optional>
#include <set>
#include <sys/stat.h>
#include <unistd.h>

#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::io {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void cannot(std::string_view verb, const fs::path& path, std::string_view why) {
  throw InvalidArgument(fmt::format("cannot {} '{}': {}", verb, path.string(), why));
}

/// A file descriptor closed on scope exit.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

void write_all(int fd, std::string_view content, const fs::path& path) {
  while (!content.empty()) {
    const ssize_t written = ::write(fd, content.data(), content.size());
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) cannot("write", path, written < 0 ? std::strerror(errno) : "no space written");
    content.remove_prefix(static_cast<std::size_t>(written));
  }
}

mode_t new_file_mode() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

/// A complete file under no name (O_TMPFILE) or a short hidden name in `dir`.
struct Unnamed {
  Descriptor fd;
  fs::path hidden;  // empty for O_TMPFILE
};

Unnamed create_unnamed(const fs::path& dir, const fs::path& target) {
  const int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd >= 0) return {Descriptor(fd), {}};
  if (errno != EOPNOTSUPP && errno != EISDIR && errno != EINVAL) cannot("write", target, std::strerror(errno));
  std::string name = (dir / ".specula-XXXXXX").string();
  const int named = ::mkstemp(name.data());
  if (named < 0) cannot("write", target, std::strerror(errno));
  return {Descriptor(named), fs::path(name)};
}

/// Links the unnamed file into `dir` under a fresh short name; returns it.
fs::path name_it(const Unnamed& file, const fs::path& dir, const fs::path& target) {
  if (!file.hidden.empty()) return file.hidden;
  static std::atomic<unsigned> counter = 0;
  const std::string proc = fmt::format("/proc/self/fd/{}", file.fd.get());
  for (int attempt = 0; attempt < 100; ++attempt) {
    const fs::path name = dir / fmt::format(".specula-{}-{}", ::getpid(), counter++);
    if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, name.c_str(), AT_SYMLINK_FOLLOW) == 0) return name;
    if (errno != EEXIST) cannot("write", target, std::strerror(errno));
  }
  cannot("write", target, "no free temporary name");
}

void write_regular(const fs::path& path, std::string_view content, const struct stat* existing) {
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  Unnamed file = create_unnamed(dir, path);
  const auto forget_hidden = [&] {
    if (!file.hidden.empty()) ::unlink(file.hidden.c_str());
  };
  try {
    write_all(file.fd.get(), content, path);
    if (::fchmod(file.fd.get(), existing ? existing->st_mode & 07777 : new_file_mode()) != 0)
      cannot("write", path, std::strerror(errno));
    check_interrupt();
  } catch (...) {
    forget_hidden();
    throw;
  }
  const fs::path name = name_it(file, dir, path);
  if (::rename(name.c_str(), path.c_str()) != 0) {
    const int error = errno;
    ::unlink(name.c_str());
    cannot("write", path, std::strerror(error));
  }
}

void write_special(const fs::path& path, std::string_view content) {
  Descriptor fd(::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) cannot("write", path, std::strerror(errno));
  check_interrupt();
  write_all(fd.get(), content, path);
}

}  // namespace

std::string read_file(const fs::path& path, std::size_t max_bytes) {
  Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) cannot("read", path, std::strerror(errno));
  struct stat info {};
  if (::fstat(fd.get(), &info) != 0) cannot("read", path, std::strerror(errno));
  if (S_ISDIR(info.st_mode)) cannot("read", path, "it is a directory");
  const auto too_large = [&] { cannot("read", path, fmt::format("larger than {} bytes, the most specula reads", max_bytes)); };
  if (S_ISREG(info.st_mode) && static_cast<std::size_t>(info.st_size) > max_bytes) too_large();
  std::string bytes;
  char buffer[1 << 16];
  while (true) {
    const ssize_t got = ::read(fd.get(), buffer, sizeof buffer);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) cannot("read", path, std::strerror(errno));
    if (got == 0) return bytes;
    if (bytes.size() + static_cast<std::size_t>(got) > max_bytes) too_large();
    bytes.append(buffer, static_cast<std::size_t>(got));
  }
}

void write_file_atomically(const fs::path& path, std::string_view content) {
  if (path.empty()) cannot("write", path, "empty file name");
  struct stat link {};
  if (::lstat(path.c_str(), &link) != 0) {
    if (errno != ENOENT) cannot("write", path, std::strerror(errno));
    return write_regular(path, content, nullptr);
  }
  fs::path target = path;
  if (S_ISLNK(link.st_mode)) {
    std::error_code ec;
    target = fs::canonical(path, ec);
    if (ec) cannot("write", path, "it is a symbolic link to a missing file");
  }
  struct stat info {};
  if (::stat(target.c_str(), &info) != 0) cannot("write", path, std::strerror(errno));
  if (S_ISDIR(info.st_mode)) cannot("write", path, "it is a directory");
  if (S_ISREG(info.st_mode)) return write_regular(target, content, &info);
  write_special(target, content);
}

namespace {

constexpr std::string_view kStagingTag = ".specula-";

/// ".NAME.specula-" for target NAME: the prefix of its staging directories.
std::string staging_prefix(const fs::path& target) {
  return fmt::format(".{}{}", target.filename().string(), kStagingTag);
}

/// Removes the staging directories of `target` whose process has ended (a killed run's).
void remove_stale_staging(const fs::path& target) {
  const fs::path dir = target.parent_path();
  const std::string prefix = staging_prefix(target);
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.starts_with(prefix)) continue;
    const std::string digits = name.substr(prefix.size());
    if (digits.empty() || digits.find_first_not_of("0123456789") != std::string::npos || digits.size() > 9) continue;
    const auto pid = static_cast<pid_t>(std::stol(digits));
    if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH) fs::remove_all(entry.path(), ec);
  }
}

}  // namespace

namespace {

/// `target` absolute, its symbolic links resolved, without "." or ".." or a final '/'.
fs::path normalized(const fs::path& target) {
  std::error_code ec;
  fs::path path = fs::absolute(target, ec);
  if (ec) cannot("write", target, ec.message());
  struct stat link {};
  const fs::path unslashed = path.filename().empty() ? path.parent_path() : path;
  if (::lstat(unslashed.c_str(), &link) == 0 && S_ISLNK(link.st_mode) && !fs::exists(unslashed, ec))
    cannot("write", target, "it is a symbolic link to a missing directory");
  path = fs::weakly_canonical(path, ec);
  if (ec) cannot("write", target, ec.message());
  while (path.filename().empty() && path != path.root_path()) path = path.parent_path();
  return path;
}

/// The names a manifest lists, if `dir` has one of `command`'s; nullopt if it has none.
std::optional<std::set<std::string>> manifest_names(const fs::path& dir, std::string_view command, bool& other_command) {
  other_command = false;
  std::ifstream in(dir / kManifestName);
  if (!in) return std::nullopt;
  std::string line;
  if (!std::getline(in, line) || line != fmt::format("specula {}", command)) {
    other_command = true;
    return std::nullopt;
  }
  std::set<std::string> names;
  while (std::getline(in, line))
    if (!line.empty()) names.insert(line);
  return names;
}

/// Refuses a target that a new output may not replace (StagedDirectory's rules).
void check_replaceable(const fs::path& target, const fs::path& requested, OutputKind kind) {
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (!ec) {
    const auto [t, c] = std::ranges::mismatch(target, cwd);
    if (t == target.end())
      cannot("write", requested, "it is the working directory or holds it; name a new directory for the output");
  }
  if (!fs::exists(target, ec)) return;
  if (!fs::is_directory(target, ec)) cannot("write", requested, "it is not a directory");
  if (fs::is_empty(target, ec)) return;
  bool other_command = false;
  if (manifest_names(target, kind.command, other_command)) return;
  if (other_command) cannot("write", requested, fmt::format("it holds another command's output, not `specula {}`'s", kind.command));
  if (fs::exists(target / kind.marker, ec)) return;
  cannot("write", requested,
         fmt::format("it is not empty and not an earlier output of `specula {}` (no {} or {}); name a new or empty "
                     "directory: specula never replaces files it did not write",
                     kind.command, kManifestName, kind.marker));
}

/// Moves the entries of `from` that specula did not write (not in `written`; all of them for an
/// output from before manifests) and that `to` does not hold into `to`.
void carry_user_files(const fs::path& from, const fs::path& to, const std::optional<std::set<std::string>>& written) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(from, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == kManifestName || (written && written->contains(name))) continue;
    if (::access((to / name).c_str(), F_OK) == 0 || errno != ENOENT) continue;
    if (::rename(entry.path().c_str(), (to / name).c_str()) != 0)
      cannot("write", to, fmt::format("keeping '{}' failed: {}", entry.path().string(), std::strerror(errno)));
  }
}

void write_manifest(const fs::path& dir, std::string_view command) {
  std::set<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) names.insert(entry.path().filename().string());
  if (ec) cannot("write", dir, ec.message());
  std::string text = fmt::format("specula {}\n", command);
  for (const auto& name : names) text += name + "\n";
  write_file_atomically(dir / kManifestName, text);
}

}  // namespace

StagedDirectory::StagedDirectory(const fs::path& target, OutputKind kind) : command_(kind.command) {
  if (target.empty()) cannot("write", target, "empty directory name");
  target_ = normalized(target);
  check_replaceable(target_, target, kind);
  std::error_code ec;
  for (fs::path p = target_.parent_path(); !fs::exists(p, ec) && p != p.root_path(); p = p.parent_path())
    created_.insert(created_.begin(), p);
  if (!created_.empty() && !fs::create_directories(target_.parent_path(), ec)) {
    created_.clear();
    cannot("write", target, ec.message());
  }
  remove_stale_staging(target_);
  staging_ = target_.parent_path() / fmt::format("{}{}", staging_prefix(target_), ::getpid());
  fs::remove_all(staging_, ec);
  if (::mkdir(staging_.c_str(), 0777) != 0) {
    const int error = errno;
    discard();
    cannot("write", target, std::strerror(error));
  }
}

StagedDirectory::~StagedDirectory() { discard(); }

void StagedDirectory::discard() noexcept {
  std::error_code ignored;
  fs::remove_all(staging_, ignored);  // uncommitted: the new files; committed: the old directory
  if (committed_) return;
  for (auto p = created_.rbegin(); p != created_.rend(); ++p) fs::remove(*p, ignored);  // each only if empty
  created_.clear();
}

void StagedDirectory::commit() {
  if (committed_) return;
  check_interrupt();
  std::error_code ec;
  write_manifest(staging_, command_);
  const bool replacing = fs::is_directory(target_, ec);
  bool other_command = false;
  const auto written = replacing ? manifest_names(target_, command_, other_command) : std::nullopt;
  if (replacing) carry_user_files(target_, staging_, written);
  const int swapped = replacing ? ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE)
                                : ::rename(staging_.c_str(), target_.c_str());
  if (swapped != 0) cannot("write", target_, std::strerror(errno));
  committed_ = true;
  if (replacing) carry_user_files(staging_, target_, written);  // any the user added during the swap
}

}  // namespace specula::io
