// specula sample: importance samples of a model, as CSV, for checking with any tool.
#include <fmt/format.h>

#include "cli.h"
#include "specula/analysis/albedo.h"
#include "specula/brdf/directions.h"
#include "specula/exceptions.h"
#include "specula/sampling/sampler.h"

namespace specula::cli {
namespace {

// The documented cap: 1e6 rows (about 80 MB of CSV, a second or two).
constexpr std::size_t kMaxCount = 1'000'000;

struct SampleOptions {
  ModelOptions model;
  double theta_i = 0;
  std::size_t count = 1000;
  std::uint64_t seed = 1;
  std::string out;
};

std::string samples_csv(const SampleOptions& o) {
  analysis::require_incidence_deg(o.theta_i, "--theta-i");
  const sampling::Sampler sampler(o.model.make());
  const double theta = radians(o.theta_i);
  const Vec3 wi{std::sin(theta), 0, std::cos(theta)};
  std::string text = "x,y,z,pdf,weight\n";
  text.reserve(text.size() + o.count * 90);
  for (const sampling::Sample& s : sampling::draw_samples(sampler, wi, o.count, o.seed))
    text += fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", s.wo.x, s.wo.y, s.wo.z, s.pdf, s.weight);
  return text;
}

}  // namespace

void add_sample_command(CLI::App& app) {
  auto o = std::make_shared<SampleOptions>();
  auto* cmd = app.add_subcommand("sample", "Importance-sample a model: directions ω_o with their pdf and weight, as CSV");
  o->model.add_to(*cmd);
  o->model.add_coef_to(*cmd);
  cmd->add_option("--theta-i", o->theta_i, "The light's polar angle in degrees, [0, 90)")->capture_default_str();
  cmd->add_option("--count,-n", o->count, "Samples to draw, [1, 1e6]")
      ->capture_default_str()->check(CLI::Range(std::size_t{1}, kMaxCount));
  cmd->add_option("--seed", o->seed, "Seed: the same seed gives the same samples, whatever the thread count")
      ->capture_default_str();
  cmd->add_option("--out,-o", o->out, "Write to FILE (atomically) instead of stdout");
  cmd->footer(
      "Columns x,y,z,pdf,weight: ω_o in the frame N = +z with the light ω_i in the xz-plane at φ = 0\n"
      "(ω_i = (sin θ_i, 0, cos θ_i)), its density per solid angle, and weight = f(ω_i, ω_o) cos θ_o / pdf.\n"
      "A draw that leaves the hemisphere is a row with pdf = weight = 0: the mean of the weight column\n"
      "estimates the albedo ρ(θ_i). How each model is sampled: docs/sampling.md. Examples:\n"
      "  specula sample --model ggx -p alpha=0.2 --theta-i 60 --count 100000 -o ggx.csv\n"
      "  specula sample --model log-normalized -p n=50 --theta-i 30 --seed 7");
  cmd->callback([o] { write_output(o->out, samples_csv(*o)); });
}

}  // namespace specula::cli
