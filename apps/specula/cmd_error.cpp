// specula error: how well one lobe approximates another, per n (the paper's Figs. 3 and 4).
#include "cli.h"

namespace specula::cli {
namespace {

// The documented cap: each n is two exact maximum searches (milliseconds); Ctrl-C stops them.
constexpr std::size_t kMaxN = 10'000;

struct ErrorOptions {
  ModelOptions model;
  OutputOptions output;
  std::string reference = "phong";
  std::string n = "1:1000@50:log";
  double zone = 0.5;
};

io::Table error_table(const ErrorOptions& o) {
  const queries::ErrorQuery q{o.model.id, o.model.param_values(), o.reference, option_values("--n", o.n, kMaxN), o.zone};
  return queries::error_table(q, queries::Spelling::option);
}

}  // namespace

void add_error_command(CLI::App& app) {
  auto o = std::make_shared<ErrorOptions>();
  auto* cmd = app.add_subcommand("error", "Approximation error of a lobe against a reference lobe, per n");
  o->model.add_to(*cmd, false);
  cmd->add_option("--reference,-r", o->reference, "The reference lobe model")->capture_default_str();
  cmd->add_option("--n", o->n, "Exponents: list or range, at most 10000 values")->capture_default_str();
  cmd->add_option("--zone", o->zone, "The epicenter: where the reference ≥ zone × its peak; zone in (0, 1)")->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  o->output.add_to(*cmd);
  cmd->footer(
      "Compares the bare lobes F(c) (no coefficient) at the same n. max_abs = max |F − F_ref| and\n"
      "argmax_abs_deg = the angle acos(c) where it occurs; max_rel_epicenter = max |F − F_ref|/F_ref\n"
      "where F_ref ≥ zone; max_rel_attenuation = the same where 0 < F_ref < zone (astronomical or inf:\n"
      "unbounded, as for Schlick's tail against c^n).\n"
      "Maxima are exact (dense sampling in u = −ln c, then golden-section refinement). Examples:\n"
      "  specula error --model log --reference phong --n 1:1000@50:log      # the paper's Figs. 3-4\n"
      "  specula error --model schlick --reference phong --n 2,20 --format json");
  cmd->callback([o] { o->output.emit(error_table(*o)); });
}

}  // namespace specula::cli
