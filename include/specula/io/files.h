#pragma once
// Reading input files with a size cap, and writing outputs so that no reader, crash or kill ever
// sees half of one. The rules (docs/files.md):
//   - Inputs are read whole, up to kMaxInputBytes; a larger one (or an endless one: /dev/zero, a
//     FIFO that never closes its end) is refused with "cannot read 'P': larger than … bytes".
//   - A regular file (or a new name) is written as an unnamed temporary file in the target's
//     directory (Linux O_TMPFILE, which no kill can leave behind), given a name only once
//     complete, then renamed over the target. Where O_TMPFILE is missing, a short hidden name
//     (".specula-XXXXXX") is used and removed on any failure.
//   - A FIFO, a character device or a socket (/dev/null, /dev/stdout, a named pipe) is written to
//     directly: it is never replaced by a regular file.
//   - A symbolic link is followed: its target is written by the rules above and the link stays.
//     A link whose target does not exist is refused.
//   - A directory is refused.
//   - When a stop was requested (Ctrl-C, SIGTERM: specula/interrupt) before the file is named,
//     it is not named: Interrupted is thrown and nothing appears.
//   - A directory of outputs (the report) is built under a hidden name beside it and swapped in
//     whole (StagedDirectory): the old one or the new one, never a mix.
// A replaced file keeps its permissions; a new one gets 0666 less the umask. Errors are one
// InvalidArgument line: "cannot write 'P': reason" / "cannot read 'P': reason".
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace specula::io {

/// The largest input file specula reads (CSV, OBJ, EXR probes, model files): 256 MiB.
inline constexpr std::size_t kMaxInputBytes = std::size_t{256} << 20;

/// The bytes of `path` (a regular file, a FIFO, a device; not a directory), at most `max_bytes`.
std::string read_file(const std::filesystem::path& path, std::size_t max_bytes = kMaxInputBytes);

/// Writes `content` to `path` by the rules above.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// Which command's output a staged directory is: the command, and a file every output of it
/// holds (how an output written before manifests existed is recognised).
struct OutputKind {
  std::string_view command;  ///< "design", "report"
  std::string_view marker;   ///< "design.json", "fig5-normalization.csv"
};

/// The manifest of an output directory: "specula COMMAND" on its first line, then the names
/// (top level) of the files and folders that specula wrote there, one per line.
inline constexpr std::string_view kManifestName = ".specula-output";

/// A directory built under a hidden name beside `target` (".NAME.specula-PID") and swapped in
/// whole by commit() (renameat2 RENAME_EXCHANGE when `target` exists): readers see the old
/// directory or the new one, never a mix. What it may replace, checked when constructed (before
/// any work): a directory that does not exist, an empty one, or an earlier output of the same
/// command (its manifest names the command; or, written before manifests, it holds the kind's
/// marker). Everything else (a file, a directory of other files, the working directory or one
/// that holds it) is refused. Files and folders that specula did not write there (not in the old
/// manifest) are moved into the new directory: a new output never removes what a user put there.
/// `target` is normalized first ("DIR/", "a/../DIR", a symbolic link to a directory all name the
/// directory itself). Destroyed uncommitted (an error, a stop), it removes what was written, and
/// the parent folders it created. The staging directories of killed runs (their process gone)
/// are removed by the next run that stages the same target.
class StagedDirectory {
 public:
  /// Throws InvalidArgument naming `target` and the reason when it may not be replaced or cannot
  /// be staged.
  StagedDirectory(const std::filesystem::path& target, OutputKind kind);
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  /// Where to write the new directory's files.
  const std::filesystem::path& path() const noexcept { return staging_; }
  /// The directory that commit() replaces, normalized.
  const std::filesystem::path& target() const noexcept { return target_; }
  /// Writes the manifest, moves the user's files across and swaps the staged directory in for
  /// `target` (the old output is removed afterwards).
  void commit();

 private:
  void discard() noexcept;

  std::filesystem::path target_, staging_;
  std::string command_;
  std::vector<std::filesystem::path> created_;  ///< parent folders made for target, outermost first
  bool committed_ = false;
};

}  // namespace specula::io
