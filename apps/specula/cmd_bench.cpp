// specula bench: the lobe benchmark (cost/lobe_cost.h) from the shipped binary.
#include <fmt/format.h>

#include "cli.h"
#include "specula/cost/lobe_cost.h"
#include "specula/models/model.h"

namespace specula::cli {
namespace {

struct BenchOptions {
  bool quick = false;
  std::string format = "table";
  double n = 20;
  bool verbose = false;
  std::string out;
};

}  // namespace

void add_bench_command(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  auto* cmd = app.add_subcommand("bench", "Time every lobe: scalar libm against SIMD exact and fast, with limits");
  cmd->add_flag("--quick", o->quick, "A few seconds: 16 MiB streams, short trials (full: 256 MiB, under a minute)");
  cmd->add_option("--format", o->format, "table (for people) or json (per lobe and tier)")->capture_default_str()
      ->check(CLI::IsMember({"table", "json"}));
  cmd->add_option("--n", o->n, "The lobes' exponent")->capture_default_str()->check(CLI::Range(1e-3, 1e9));
  cmd->add_option("--out,-o", o->out, "Write to FILE (atomically) instead of stdout");
  cmd->add_flag("--verbose,-v", o->verbose, "Print each phase to stderr as it starts");
  cmd->footer(
      "Per lobe: ns per evaluation through the scalar lobe (libm) and the SIMD exact and fast tiers, in cache\n"
      "and streaming, on one core and on all; evaluations/s per core; accuracy against the scalar double lobe\n"
      "and against cⁿ; the compute and memory limits and each lobe's distance from the nearer. Timings are of\n"
      "this machine now: compare the ratios. docs/simd.md explains every column. User lobe models (--models\n"
      "FILE) are measured beside the built-ins: scalar = the formula per value, exact and fast = the\n"
      "vectorized formula path. Examples:\n"
      "  specula bench --quick\n"
      "  specula bench --models examples/models/builtin-copies.toml\n"
      "  specula bench --format json | jq '.lobes.log.fast.evals_per_s_per_core'");
  cmd->callback([o] {
    cost::Settings settings = (o->quick ? cost::Settings::quick() : cost::Settings::full()).with_registered_user_lobes();
    settings.n = o->n;
    auto progress = [verbose = o->verbose](std::string_view phase) {
      if (verbose) fmt::print(stderr, "bench: {}\n", phase);
    };
    const cost::Result result = cost::run(settings, progress);
    write_output(o->out, o->format == "json" ? cost::to_json(result) : cost::to_table(result));
  });
}

}  // namespace specula::cli
