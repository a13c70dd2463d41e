// specula report: the paper reproduced end to end, as report/index.html.
#include <fmt/format.h>

#include "cli.h"
#include "gpu_timer.h"
#include "specula/report/report.h"

namespace specula::cli {

void add_report_command(CLI::App& app) {
  auto options = std::make_shared<report::Options>();
  auto* cmd = app.add_subcommand("report", "Write the report: the paper's figures regenerated (HTML + CSV)");
  cmd->add_option("--out,-o", options->out_dir, "Output folder (default: report)");
  cmd->add_flag("--quick", options->quick, "Smaller sweeps, for tests");
  auto gpu_timing = std::make_shared<bool>(true);
  cmd->add_flag("!--no-gpu-timing", *gpu_timing,
                "Do not time F_log and pow on the GPU (an offscreen GL context: the GPU, or llvmpipe without one)");
  cmd->footer("Writes DIR/index.html (self-contained) and every table as CSV beside it.\n"
              "Example:\n  specula report --out report && xdg-open report/index.html");
  cmd->callback([options, gpu_timing] {
    if (*gpu_timing) options->gpu_timer = time_on_gpu;
    options->progress = [](std::string_view section) { fmt::print(stderr, "report: {}\n", section); };
    report::write_report(*options);
    fmt::print(stderr, "report: wrote {}\n", (options->out_dir / "index.html").string());
  });
}

}  // namespace specula::cli
