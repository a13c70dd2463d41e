#pragma once
// The report: the paper reproduced from specula's own computations, as one self-contained HTML
// page plus every table beside it (CSV).
#include <filesystem>
#include <functional>
#include <string_view>

#include "specula/design/design.h"

namespace specula::report {

struct Options {
  std::filesystem::path out_dir = "report";
  bool quick = false;
  /// Times the paper's lobes (F_log, pow) and the designed ones on a GPU for the verdict on the
  /// paper's premise (the CLI's: an offscreen GL context); empty: the CPU's costs only.
  design::GpuTimer gpu_timer = {};
  /// Called with a line for each section as it starts.
  std::function<void(std::string_view)> progress = [](std::string_view) {};
};

/// Writes out_dir/index.html and the tables, all at once: the files are made in a staging
/// directory beside out_dir and swapped in when complete (io::StagedDirectory), so a failed,
/// stopped or killed run leaves the previous report. Throws InvalidArgument when out_dir is
/// unusable.
void write_report(const Options& options);

}  // namespace specula::report
