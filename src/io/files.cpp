#include "specula/io/files.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <fcntl.h>
#include <signal.h>
#include <fmt/format.h>
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

StagedDirectory::StagedDirectory(const fs::path& target) {
  if (target.empty()) cannot("write", target, "empty directory name");
  std::error_code ec;
  target_ = fs::absolute(target, ec);
  struct stat info {};
  if (!ec && ::lstat(target_.c_str(), &info) == 0) {
    if (S_ISLNK(info.st_mode)) target_ = fs::canonical(target_, ec);
    if (!ec && !fs::is_directory(target_, ec)) cannot("write", target, "it is not a directory");
  }
  if (ec) cannot("write", target, ec.message());
  if (!fs::is_directory(target_.parent_path()) && !fs::create_directories(target_.parent_path(), ec))
    cannot("write", target, ec.message());
  remove_stale_staging(target_);
  staging_ = target_.parent_path() / fmt::format("{}{}", staging_prefix(target_), ::getpid());
  fs::remove_all(staging_, ec);
  if (::mkdir(staging_.c_str(), 0777) != 0) cannot("write", target, std::strerror(errno));
}

StagedDirectory::~StagedDirectory() {
  std::error_code ignored;
  fs::remove_all(staging_, ignored);  // uncommitted: the new files; committed: the old directory
}

void StagedDirectory::commit() {
  if (committed_) return;
  check_interrupt();
  std::error_code ec;
  const int swapped = fs::is_directory(target_, ec)
                          ? ::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE)
                          : ::rename(staging_.c_str(), target_.c_str());
  if (swapped != 0) cannot("write", target_, std::strerror(errno));
  committed_ = true;
}

}  // namespace specula::io
