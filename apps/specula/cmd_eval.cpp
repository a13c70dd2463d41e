// specula eval: a model's value at cosines (lobe models) or at directions (any model).
#include <fmt/format.h>

#include "cli.h"
#include "specula/exceptions.h"

namespace specula::cli {
namespace {

struct EvalOptions {
  ModelOptions model;
  OutputOptions output;
  std::string cos;
  bool bare_lobe = false;
  std::optional<double> theta_i;
  std::string theta_o;
  double phi_o = 0;
};

constexpr auto kOption = queries::Spelling::option;

io::Table evaluated(const Model& m, const EvalOptions& o) {
  if (o.cos.empty())
    return queries::eval_at_directions(m, *o.theta_i, option_values("--theta-o", o.theta_o), o.phi_o, kOption);
  return queries::eval_at_cosines(m, option_values("--cos", o.cos), o.bare_lobe, kOption);
}

}  // namespace

void add_eval_command(CLI::App& app) {
  auto o = std::make_shared<EvalOptions>();
  auto* cmd = app.add_subcommand("eval", "Evaluate a model at cosines or at directions");
  o->model.add_to(*cmd);
  o->model.add_coef_to(*cmd);
  auto* cos = cmd->add_option("--cos,-c", o->cos,
                              "Cosines: list or range (1,0.5  0:1@11  0.9:1@5:log); lobe models only");
  cmd->add_flag("--lobe", o->bare_lobe, "With --cos: print the bare lobe F(c) instead of k·F(c)");
  auto* theta_i = cmd->add_option("--theta-i", o->theta_i, "Light's polar angle in degrees, [0, 90]");
  auto* theta_o = cmd->add_option("--theta-o", o->theta_o, "Viewer's polar angles in degrees: list or range");
  cmd->add_option("--phi-o", o->phi_o, "Viewer's azimuth in degrees (0: plane of incidence, the light at 0°)");
  theta_i->needs(theta_o);
  theta_o->needs(theta_i);
  cos->excludes(theta_i)->excludes(theta_o);
  o->output.add_to(*cmd);
  cmd->footer(
      "Prints cos,value with value = k·F(c) (k = the model's coefficient), or theta_o_deg,value\n"
      "with value = f(L, V) for L at --theta-i and V at (--theta-o, --phi-o), N = +z.\nExamples:\n"
      "  specula eval --model log -p n=20 --cos 0.9:1@11\n"
      "  specula eval --model ggx -p alpha=0.2 --theta-i 30 --theta-o 0:90:10 --format json");
  cmd->callback([o] {
    if (o->cos.empty() && !o->theta_i)
      throw InvalidArgument("give --cos LIST (lobe models) or --theta-i and --theta-o (any model)");
    o->output.emit(evaluated(o->model.make(), *o));
  });
}

}  // namespace specula::cli
