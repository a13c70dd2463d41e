#pragma once
// The one quick report that the report suites read (`ReportPage`, `BeyondThePaperTest`): made once
// per `ctest` run by the fixture test `report.quick_report` (tests/report/quick_report.cmake), as
// a user makes it, `specula --models tests/report/user_lobes.toml report --quick --out DIR`: about
// 60–90 s under the sanitizers, once instead of once per suite. A binary run by hand, without
// CTest's fixture, reads the report ctest made last, or makes one into the same folder if there
// is none: `ctest --preset debug -R '^report'` (or deleting the folder) makes it anew.
#include <cstdlib>
#include <filesystem>
#include <string>

#include <fmt/core.h>

#include "text_support.h"

namespace specula::testing {

struct QuickReport {
  std::filesystem::path dir;  ///< the report: index.html and the files beside it
  int exit_code = -1;
  std::string out, err;       ///< what the CLI printed
};

/// The command that makes the report into `folder`/report, with its streams and exit status in
/// `folder`/{stdout,stderr,exit_code}: the fixture's (quick_report.cmake) and the fallback's.
inline QuickReport quick_report() {
  const std::filesystem::path folder = SPECULA_QUICK_REPORT_DIR;
  if (!std::filesystem::exists(folder / "exit_code")) {
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    const std::string command =
        fmt::format("'{}' --models '{}' report --quick --out '{}' > '{}' 2> '{}'; echo $? > '{}'", SPECULA_CLI,
                    SPECULA_SOURCE_DIR "/tests/report/user_lobes.toml", (folder / "report").string(),
                    (folder / "stdout").string(), (folder / "stderr").string(), (folder / "exit_code").string());
    if (std::system(command.c_str()) != 0) return {};
  }
  return {folder / "report", std::stoi(read_file(folder / "exit_code")), read_file(folder / "stdout"),
          read_file(folder / "stderr")};
}

}  // namespace specula::testing
