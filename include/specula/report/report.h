#pragma once
// The report: the paper reproduced from specula's own computations, as one self-contained HTML
// page plus every table beside it (CSV).
#include <filesystem>
#include <functional>
#include <string_view>

namespace specula::report {

struct Options {
  std::filesystem::path out_dir = "report";
  bool quick = false;
  /// Called with a line for each section as it starts.
  std::function<void(std::string_view)> progress = [](std::string_view) {};
};

/// Writes out_dir/index.html and the tables, all at once: the files are made in a staging
/// directory beside out_dir and swapped in when complete (io::StagedDirectory), so a failed,
/// stopped or killed run leaves the previous report. Throws InvalidArgument when out_dir is
/// unusable.
void write_report(const Options& options);

}  // namespace specula::report
