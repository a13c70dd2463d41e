// specula verdict: which energy compensation is right — each published compensation's albedo
// against the random walk's (queries/compensation.h, docs/energy-compensation.md).
#include <fmt/format.h>

#include "cli.h"
#include "specula/exceptions.h"
#include "specula/queries/compensation.h"

namespace specula::cli {
namespace {

// The documented caps: the grid's α and μ values; Ctrl-C stops the walk.
constexpr std::size_t kMaxAxisValues = 64;

struct VerdictOptions {
  std::string alpha = "0.05,0.1,0.2,0.35,0.5,0.7,0.85,1";
  std::string mu = "0.05,0.1,0.2,0.35,0.5,0.7,0.85,1";
  std::uint64_t paths = std::uint64_t{1} << 17;
  std::uint64_t seed = 1;
  bool cells = false;
  bool quiet = false;
  OutputOptions output;
};

io::Table verdict_table(const VerdictOptions& o) {
  queries::VerdictSettings s;
  s.alpha = option_values("--alpha", o.alpha, kMaxAxisValues);
  s.mu = option_values("--mu", o.mu, kMaxAxisValues);
  for (double a : s.alpha)
    if (!(a >= 0.01 && a <= 1)) throw InvalidArgument(fmt::format("--alpha {} is outside [0.01, 1]", a));
  for (double m : s.mu)
    if (!(m > 0 && m <= 1)) throw InvalidArgument(fmt::format("--mu {} is outside (0, 1]", m));
  s.paths = o.paths;
  s.seed = o.seed;
  if (!o.quiet)
    s.progress = [next = std::size_t{1}](std::size_t done, std::size_t total) mutable {
      if (done * 10 < next * total) return;
      fmt::print(stderr, "verdict: {}% ({}/{} cells)\n", done * 100 / total, done, total);
      next = done * 10 / total + 1;
    };
  const queries::Verdict v = queries::verdict(s);
  return o.cells ? v.cells : queries::summary_table(v);
}

}  // namespace

void add_verdict_command(CLI::App& app) {
  auto o = std::make_shared<VerdictOptions>();
  auto* cmd = app.add_subcommand("verdict", "Which energy compensation is right: each one's albedo against the random walk's");
  cmd->add_option("--alpha,-a", o->alpha, "GGX roughness values, [0.01, 1]: list or range, at most 64")->capture_default_str();
  cmd->add_option("--mu", o->mu, "cos θ values, (0, 1]: list or range, at most 64")->capture_default_str();
  cmd->add_option("--paths,-n", o->paths, "Walk paths per (α, μ) cell, shared by every Fresnel")
      ->capture_default_str()->check(CLI::Range(walk::kMinPaths, std::uint64_t{1} << 26));
  cmd->add_option("--seed", o->seed, "The walk's seed")->capture_default_str();
  cmd->add_flag("--cells", o->cells, "Print every cell (α, μ, Fresnel: the inputs, the truth, each compensation's albedo) instead of the summary");
  cmd->add_flag("--quiet,-q", o->quiet, "No progress on stderr");
  o->output.add_to(*cmd);
  cmd->footer(
      "The compensations (docs/energy-compensation.md): none, kulla-conty (Kulla & Conty 2017, F_avg² E_avg /\n"
      "(1 - F_avg (1 - E_avg)) on f_ms), turquin-f0 / turquin-f / turquin-favg (Turquin 2019 with F0, F(θ), F_avg),\n"
      "cycles (albedo scaling with F_ms), walk-fit (derived from the walk), and ggx+ms, what specula ships (+ms on the\n"
      "GGX model of each Fresnel: the walk's own table, at the F0 of the same F_avg for non-Schlick kinds). Fresnels: Schlick F0 0.04-0.9, dielectrics 1.1-2.5, gold,\n"
      "copper, aluminium.\n"
      "The summary gives, per Fresnel family and compensation, the largest and RMS |albedo - walk| over the grid.\n"
      "Examples:\n"
      "  specula verdict                                   # the full grid: a minute or two\n"
      "  specula verdict --alpha 0.5,1 --mu 0.1,1 --cells --format json");
  cmd->callback([o] { o->output.emit(verdict_table(*o)); });
}

}  // namespace specula::cli
