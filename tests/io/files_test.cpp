// specula::io files (include/specula/io/files.h): atomic writes that no failure, kill or stop
// leaves half done, special files written in place, symbolic links followed, capped reads.
#include "specula/io/files.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"

namespace specula::io {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// A fresh, empty directory removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = fs::temp_directory_path() /
            fmt::format("specula-io-test-{}-{}-{}", ::getpid(), counter++,
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  std::set<std::string> listing() const {
    std::set<std::string> names;
    for (const auto& entry : fs::directory_iterator(path_)) names.insert(entry.path().filename().string());
    return names;
  }

 private:
  fs::path path_;
};

std::string contents(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}


// ---- write_file_atomically ------------------------------------------------------------------

TEST(WriteFileAtomically, WritesThenOverwritesLeavingNoTemporaryFiles) {
  TempDir dir;
  const fs::path file = dir.path() / "out.csv";
  write_file_atomically(file, "n,coef\n1,2\n");
  EXPECT_EQ(contents(file), "n,coef\n1,2\n");
  EXPECT_THAT(dir.listing(), ElementsAre("out.csv"));

  write_file_atomically(file, "short\n");  // a shorter text replaces all of the old one
  EXPECT_EQ(contents(file), "short\n");
  EXPECT_THAT(dir.listing(), ElementsAre("out.csv"));

  write_file_atomically(file, "");
  EXPECT_EQ(contents(file), "");
  EXPECT_TRUE(fs::exists(file));
  EXPECT_THAT(dir.listing(), ElementsAre("out.csv"));
}

TEST(WriteFileAtomically, WritesBinaryContentVerbatim) {
  TempDir dir;
  const fs::path file = dir.path() / "data.bin";
  std::string content = "a\r\nb\n";
  content.push_back('\0');
  content += std::string(100000, 'x');
  write_file_atomically(file, content);
  EXPECT_EQ(contents(file), content);
  EXPECT_THAT(dir.listing(), ElementsAre("data.bin"));
}

TEST(WriteFileAtomically, NonexistentDirectoryThrowsAndLeavesNothing) {
  TempDir dir;
  const fs::path file = dir.path() / "missing" / "out.csv";
  try {
    write_file_atomically(file, "text\n");
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr(file.string()));
  }
  EXPECT_FALSE(fs::exists(dir.path() / "missing"));
  EXPECT_TRUE(dir.listing().empty());
}

TEST(WriteFileAtomically, DirectoryAsTargetThrowsAndLeavesNoPartialFile) {
  TempDir dir;
  const fs::path target = dir.path() / "adir";
  fs::create_directory(target);
  fs::create_directory(target / "inside");
  try {
    write_file_atomically(target, "text\n");
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr(target.string()));
  }
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_TRUE(fs::is_directory(target / "inside"));  // the directory is untouched
  EXPECT_THAT(dir.listing(), ElementsAre("adir"));   // no temporary file beside it
}

TEST(WriteFileAtomically, EmptyPathThrows) {
  EXPECT_THROW(write_file_atomically("", "text"), InvalidArgument);
}

TEST(WriteFileAtomically, FailureKeepsTheOldContent) {
  TempDir dir;
  const fs::path file = dir.path() / "keep.txt";
  write_file_atomically(file, "old\n");
  // A file in place of a directory: dir/keep.txt/x cannot be written.
  EXPECT_THROW(write_file_atomically(file / "x", "new\n"), InvalidArgument);
  EXPECT_EQ(contents(file), "old\n");
  EXPECT_THAT(dir.listing(), ElementsAre("keep.txt"));
}

// ---- special files, links, names -----------------------------------------------------------

TEST(WriteFileAtomically, WritesIntoACharacterDeviceWithoutReplacingIt) {
  write_file_atomically("/dev/null", "discarded\n");
  struct stat info {};
  ASSERT_EQ(::stat("/dev/null", &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));  // still the device, not a regular file
}

TEST(WriteFileAtomically, WritesIntoAFifo) {
  TempDir dir;
  const fs::path fifo = dir.path() / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    received = text.str();
  });
  write_file_atomically(fifo, "through the pipe\n");
  reader.join();
  EXPECT_EQ(received, "through the pipe\n");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_THAT(dir.listing(), ElementsAre("pipe"));
}

TEST(WriteFileAtomically, FollowsASymbolicLinkAndKeepsIt) {
  TempDir dir;
  fs::create_directory(dir.path() / "real");
  const fs::path target = dir.path() / "real" / "out.csv", link = dir.path() / "link.csv";
  write_file_atomically(target, "old\n");
  fs::create_symlink(target, link);
  write_file_atomically(link, "new\n");
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(contents(target), "new\n");
  EXPECT_THAT(dir.listing(), ElementsAre("link.csv", "real"));
}

TEST(WriteFileAtomically, RefusesADanglingSymbolicLink) {
  TempDir dir;
  const fs::path link = dir.path() / "dangling";
  fs::create_symlink(dir.path() / "nowhere", link);
  try {
    write_file_atomically(link, "text\n");
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("symbolic link"));
  }
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_FALSE(fs::exists(dir.path() / "nowhere"));
}

TEST(WriteFileAtomically, KeepsTheModeOfAReplacedFile) {
  TempDir dir;
  const fs::path file = dir.path() / "script.sh";
  write_file_atomically(file, "#!/bin/sh\n");
  fs::permissions(file, fs::perms::owner_all);
  write_file_atomically(file, "#!/bin/sh\necho\n");
  EXPECT_EQ(fs::status(file).permissions() & fs::perms::all, fs::perms::owner_all);
}

TEST(WriteFileAtomically, AcceptsTheLongestFileName) {
  TempDir dir;
  const fs::path file = dir.path() / std::string(255, 'n');  // NAME_MAX on Linux file systems
  write_file_atomically(file, "long\n");
  EXPECT_EQ(contents(file), "long\n");
  EXPECT_EQ(dir.listing().size(), 1u);
}

TEST(WriteFileAtomically, AStopRequestBeforeTheNameLeavesNothing) {
  TempDir dir;
  const fs::path file = dir.path() / "out.csv";
  request_stop(SIGINT);
  EXPECT_THROW(write_file_atomically(file, "text\n"), Interrupted);
  clear_stop_request();
  EXPECT_TRUE(dir.listing().empty());
  // The control: without the request the same call writes.
  write_file_atomically(file, "text\n");
  EXPECT_THAT(dir.listing(), ElementsAre("out.csv"));
}

// A process killed (SIGKILL) while it writes a large file leaves nothing in the directory: the
// content lives in an unnamed O_TMPFILE until it is complete.
TEST(WriteFileAtomically, AKillDuringTheWriteLeavesNoFile) {
  TempDir dir;
  const fs::path file = dir.path() / "big.bin";
  const std::string content(std::size_t{400} << 20, 'x');  // long enough to be caught writing
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    write_file_atomically(file, content);
    ::_exit(0);
  }
  // Kill once the child has started writing: its unnamed file's blocks show in the directory's
  // file system, not in the directory.
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  ::kill(child, SIGKILL);
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the write finished before the kill; the test proves nothing";
  EXPECT_TRUE(dir.listing().empty());
}

// ---- read_file ------------------------------------------------------------------------------

TEST(ReadFile, ReadsAWholeFile) {
  TempDir dir;
  const fs::path file = dir.path() / "in.csv";
  write_file_atomically(file, "n,coef\n1,2\n");
  EXPECT_EQ(read_file(file), "n,coef\n1,2\n");
}

TEST(ReadFile, RefusesAFileLargerThanTheCap) {
  TempDir dir;
  const fs::path file = dir.path() / "in.csv";
  write_file_atomically(file, std::string(1001, 'x'));
  EXPECT_EQ(read_file(file, 1001).size(), 1001u);  // the control: at the cap it is read
  try {
    read_file(file, 1000);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("larger than 1000 bytes"));
  }
}

TEST(ReadFile, StopsReadingAnEndlessDevice) {
  try {
    read_file("/dev/zero", 1 << 20);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("/dev/zero"));
  }
}

TEST(ReadFile, RefusesADirectoryAndAMissingFile) {
  TempDir dir;
  EXPECT_THROW(read_file(dir.path()), InvalidArgument);
  EXPECT_THROW(read_file(dir.path() / "missing"), InvalidArgument);
}

// ---- StagedDirectory ------------------------------------------------------------------------

constexpr OutputKind kReport{"report", "index.html"};

void write_files(const fs::path& dir, const std::string& text) {
  write_file_atomically(dir / "index.html", text);
  write_file_atomically(dir / "table.csv", text);
}

void write_output(const fs::path& target, const std::string& text) {
  StagedDirectory staged(target, kReport);
  write_files(staged.path(), text);
  staged.commit();
}

/// The message StagedDirectory(target) refuses with; empty if it accepts.
std::string refusal(const fs::path& target, OutputKind kind = kReport) {
  try {
    StagedDirectory staged(target, kind);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return {};
}

TEST(StagedDirectory, CommitReplacesTheWholeOutputAndWritesItsManifest) {
  TempDir dir;
  const fs::path report = dir.path() / "report";
  write_output(report, "first\n");
  EXPECT_EQ(contents(report / "index.html"), "first\n");
  EXPECT_EQ(contents(report / kManifestName), "specula report\nindex.html\ntable.csv\n");
  {
    StagedDirectory second(report, kReport);
    write_file_atomically(second.path() / "index.html", "second\n");
    second.commit();
  }
  EXPECT_EQ(contents(report / "index.html"), "second\n");
  EXPECT_FALSE(fs::exists(report / "table.csv"));  // specula's old output went as a whole
  EXPECT_THAT(dir.listing(), ElementsAre("report"));
}

TEST(StagedDirectory, KeepsTheFilesAUserPutIntoAnEarlierOutput) {
  TempDir dir;
  const fs::path report = dir.path() / "report";
  write_output(report, "first\n");
  write_file_atomically(report / "notes.txt", "mine\n");
  fs::create_directory(report / "drafts");
  write_file_atomically(report / "drafts" / "a.txt", "mine too\n");
  write_output(report, "second\n");
  EXPECT_EQ(contents(report / "index.html"), "second\n");
  EXPECT_EQ(contents(report / "notes.txt"), "mine\n");
  EXPECT_EQ(contents(report / "drafts" / "a.txt"), "mine too\n");
  EXPECT_EQ(contents(report / kManifestName), "specula report\nindex.html\ntable.csv\n");  // still not specula's
  write_output(report, "third\n");
  EXPECT_EQ(contents(report / "notes.txt"), "mine\n");
}

TEST(StagedDirectory, RefusesADirectoryOfOtherFilesBeforeAnyWorkAndLeavesItWhole) {
  TempDir dir;
  const fs::path mine = dir.path() / "mine";
  fs::create_directory(mine);
  write_file_atomically(mine / "thesis.tex", "years of work\n");
  EXPECT_THAT(refusal(mine), HasSubstr("not empty and not an earlier output of `specula report`"));
  EXPECT_THAT(refusal(mine.string() + "/"), HasSubstr("not an earlier output"));
  fs::create_symlink(mine, dir.path() / "link");
  EXPECT_THAT(refusal(dir.path() / "link"), HasSubstr("not an earlier output"));  // through a link, the same rule
  EXPECT_EQ(contents(mine / "thesis.tex"), "years of work\n");
  EXPECT_THAT(dir.listing(), ElementsAre("link", "mine"));
  // Control: the same directory, empty, is accepted.
  fs::remove(mine / "thesis.tex");
  EXPECT_EQ(refusal(mine), "");
}

TEST(StagedDirectory, RefusesAnotherCommandsOutputAndAcceptsOneFromBeforeManifestsByItsMarker) {
  TempDir dir;
  const fs::path out = dir.path() / "out";
  write_output(out, "report\n");
  EXPECT_THAT(refusal(out, {"design", "design.json"}), HasSubstr("another command's output"));
  const fs::path old = dir.path() / "old";
  fs::create_directory(old);
  write_file_atomically(old / "index.html", "from an earlier specula\n");
  write_file_atomically(old / "figure.svg", "<svg/>\n");
  EXPECT_EQ(refusal(old), "");
  write_output(old, "new\n");
  EXPECT_EQ(contents(old / "index.html"), "new\n");
  EXPECT_EQ(contents(old / "figure.svg"), "<svg/>\n");  // not known to be specula's: kept
}

TEST(StagedDirectory, RefusesTheWorkingDirectoryAndThoseHoldingIt) {
  TempDir dir;
  const fs::path work = dir.path() / "work";
  fs::create_directory(work);
  const fs::path before = fs::current_path();
  fs::current_path(work);
  const std::string dot = refusal("."), dotdot = refusal(".."), absolute = refusal(work), root = refusal("/");
  const std::string inside = refusal("sub/");
  fs::current_path(before);
  EXPECT_THAT(dot, HasSubstr("working directory"));
  EXPECT_THAT(dotdot, HasSubstr("working directory"));
  EXPECT_THAT(absolute, HasSubstr("working directory"));
  EXPECT_THAT(root, HasSubstr("working directory"));
  EXPECT_EQ(inside, "");  // control: a new directory below it is fine
}

TEST(StagedDirectory, NormalizesATrailingSlashAndDotDot) {
  TempDir dir;
  fs::create_directory(dir.path() / "a");
  write_output(dir.path().string() + "/a/../report/", "slashed\n");
  EXPECT_EQ(contents(dir.path() / "report" / "index.html"), "slashed\n");
  EXPECT_THAT(dir.listing(), ElementsAre("a", "report"));
}

TEST(StagedDirectory, WithoutCommitTheOldDirectoryStaysAndTheStagingAndNewFoldersGo) {
  TempDir dir;
  const fs::path report = dir.path() / "report";
  write_output(report, "old\n");
  {
    StagedDirectory failed(report, kReport);
    write_files(failed.path(), "new\n");
  }
  EXPECT_EQ(contents(report / "index.html"), "old\n");
  {
    StagedDirectory failed(dir.path() / "x" / "y" / "report", kReport);
    EXPECT_TRUE(fs::is_directory(dir.path() / "x" / "y"));
  }
  EXPECT_THAT(dir.listing(), ElementsAre("report"));  // x and y were made for it, and went with it
}

TEST(StagedDirectory, AKilledRunLeavesTheOldDirectoryAndTheNextRunRemovesItsStaging) {
  TempDir dir;
  const fs::path report = dir.path() / "report";
  write_output(report, "old\n");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    StagedDirectory staged(report, kReport);
    write_files(staged.path(), "half\n");
    ::kill(::getpid(), SIGKILL);  // killed before commit
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(contents(report / "index.html"), "old\n");
  EXPECT_EQ(dir.listing().size(), 2u);  // report and the killed run's staging directory
  {
    StagedDirectory next(report, kReport);
    EXPECT_EQ(dir.listing().size(), 2u);  // report and this run's own staging: the stale one is gone
  }
  EXPECT_THAT(dir.listing(), ElementsAre("report"));
}

TEST(StagedDirectory, RefusesAFileInPlaceOfTheDirectory) {
  TempDir dir;
  write_file_atomically(dir.path() / "report", "a file\n");
  EXPECT_THAT(refusal(dir.path() / "report"), HasSubstr("not a directory"));
  EXPECT_EQ(contents(dir.path() / "report"), "a file\n");
}

}  // namespace
}  // namespace specula::io
