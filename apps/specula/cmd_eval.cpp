// specula eval: a model's value at cosines (lobe models) or at directions (any model).
#include <fmt/format.h>

#include "cli.h"
#include "specula/brdf/directions.h"
#include "specula/error.h"
#include "specula/io/values.h"

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

io::Table eval_at_cosines(const Model& m, const EvalOptions& o) {
  if (!m.is_lobe())
    throw InvalidArgument(fmt::format(
        "model '{}' is a full BRDF: give directions with --theta-i and --theta-o", m.id()));
  io::Table table{{"cos", "value"}, {}, model_meta(m)};
  for (const double c : option_values("--cos", o.cos)) {
    if (c < -1 || c > 1) throw InvalidArgument(fmt::format("--cos {} is outside [-1, 1]", c));
    table.rows.push_back({c, o.bare_lobe ? lobes::eval(m.lobe(), c) : m.at_cos(c)});
  }
  return table;
}

void check_polar(double degrees, const char* option) {
  if (!(degrees >= 0 && degrees <= 90))  // NaN too
    throw InvalidArgument(fmt::format("{} {} is outside [0, 90] degrees", option, degrees));
}

io::Table eval_at_directions(const Model& m, const EvalOptions& o) {
  check_polar(*o.theta_i, "--theta-i");
  if (!(o.phi_o >= -360 && o.phi_o <= 360))  // NaN too
    throw InvalidArgument(fmt::format("--phi-o {} is outside [-360, 360] degrees", o.phi_o));
  const Vec3 n{0, 0, 1};
  const Vec3 l = from_spherical(radians(*o.theta_i), 0.0);
  io::Table table{{"theta_o_deg", "value"}, {}, model_meta(m)};
  table.meta.emplace_back("theta_i_deg", io::format_number(*o.theta_i));
  table.meta.emplace_back("phi_o_deg", io::format_number(o.phi_o));
  for (const double theta_o : option_values("--theta-o", o.theta_o)) {
    check_polar(theta_o, "--theta-o");
    table.rows.push_back({theta_o, m(n, l, from_spherical(radians(theta_o), radians(o.phi_o)))});
  }
  return table;
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
    const Model m = o->model.make();
    o->output.emit(o->cos.empty() ? eval_at_directions(m, *o) : eval_at_cosines(m, *o));
  });
}

}  // namespace specula::cli
