// specula albedo: directional albedo ρ(θ_i), by cubature or by Monte Carlo.
#include <fmt/format.h>

#include "cli.h"
#include "specula/exceptions.h"

namespace specula::cli {
namespace {

// The documented caps: angles, and Monte-Carlo samples over all angles (~1e8 per second and core
// for the cheap models); Ctrl-C stops either.
constexpr std::size_t kMaxAngles = 10'000;
constexpr double kMaxTotalSamples = 1e10;

struct AlbedoOptions {
  ModelOptions model;
  OutputOptions output;
  std::string theta = "0:80:10,85,89";
  std::string method = "cubature";
  std::uint64_t samples = 1'000'000;
  std::uint64_t seed = 1;
};

io::Table albedo_table(const AlbedoOptions& o) {
  const queries::AlbedoQuery q{option_values("--theta", o.theta, kMaxAngles),
                               queries::albedo_method_named(o.method, queries::Spelling::option), o.samples, o.seed};
  const double total = static_cast<double>(q.samples) * static_cast<double>(q.theta_deg.size());
  if (queries::samples(q.method) && total > kMaxTotalSamples)
    throw InvalidArgument(fmt::format("--samples {} at {} angles is more than {:g} samples in all", q.samples,
                                      q.theta_deg.size(), kMaxTotalSamples));
  return queries::albedo_table(o.model.make(), q, queries::Spelling::option);
}

}  // namespace

void add_albedo_command(CLI::App& app) {
  auto o = std::make_shared<AlbedoOptions>();
  auto* cmd = app.add_subcommand("albedo", "Directional albedo ρ(θ_i): the energy reflected for light from θ_i");
  o->model.add_to(*cmd);
  o->model.add_coef_to(*cmd);
  cmd->add_option("--theta,-t", o->theta, "Incidence angles in degrees, [0, 90): list or range, at most 10000 angles")->capture_default_str();
  cmd->add_option("--method", o->method,
                  "cubature (deterministic, 8+ digits); monte-carlo (the importance-sampled cross-check); or\n"
                  "one of BRDF Explorer's estimators: uniform, cosine, sampler (the model's own), mis (sampler\n"
                  "and cosine, balance heuristic). The sampling methods add standard_error")->capture_default_str()
      ->check(one_of<queries::AlbedoMethod, queries::kAlbedoMethodCount>());
  cmd->add_option("--samples", o->samples, "Monte-Carlo samples per angle, [1, 1e9]; at most 1e10 over all angles")->capture_default_str()->check(CLI::Range(1, 1'000'000'000));
  cmd->add_option("--seed", o->seed, "Monte-Carlo seed")->capture_default_str();
  o->output.add_to(*cmd);
  cmd->footer(
      "ρ(θ_i) = ∫ f(L, V) (N·V) dω_V over the hemisphere; a BRDF conserves energy when ρ ≤ 1 at\n"
      "every θ_i. Examples:\n"
      "  specula albedo --model log-normalized -p n=20 --theta 0:85:5\n"
      "  specula albedo --model log-normalized -p n=20 --form nh --theta 0   # k made for rv, used in nh\n"
      "  specula albedo --model ggx -p alpha=0.1 --theta 0,60,89 --method monte-carlo --samples 100000\n"
      "  specula albedo --model ggx -p alpha=0.1 --theta 60 --method uniform --samples 100000   # its variance");
  cmd->callback([o] { o->output.emit(albedo_table(*o)); });
}

}  // namespace specula::cli
