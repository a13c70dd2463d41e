#include "environment_job.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <tbb/task_arena.h>

#include "fields.h"
#include "specula/exceptions.h"
#include "specula/io/base64.h"
#include "specula/render/image_io.h"
#include "specula/sampling/seeds.h"

namespace specula::serve {
namespace {

using Json = nlohmann::ordered_json;

struct EnvironmentJob final : Job {
  explicit EnvironmentJob(render::Scene s) : scene(std::move(s)) {}

  render::Scene scene;
  std::shared_ptr<const render::Environment> environment;
  render::RenderSettings size;
  render::EnvironmentSettings settings;  ///< samples: the target per pixel
  std::string mesh_name, probe_name;
  render::Display display;
  // Guarded by `mutex`:
  int done = 0;
  std::string png;  ///< base64 of the image so far
  double seconds = 0;

  std::string run() override {
    const auto start = std::chrono::steady_clock::now();
    std::vector<double> sum(std::size_t(3) * size.width * size.height, 0.0);
    tbb::task_arena one_core(1);  // a render never takes more than one core from the requests
    for (int pass = 0; done < settings.samples && !cancel; ++pass) {
      const int n = pass_samples(pass, done, settings.samples);
      const render::Image image = one_core.execute([&] {
        return render::render_environment(scene, *environment, size,
                                          {n, sampling::stream_key(settings.seed, std::uint64_t(pass)), settings.estimator});
      });
      const auto samples = image.samples();
      for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += double(samples[i]) * n;
      const std::string frame = io::base64(render::png_bytes(mean(sum, done + n), display));
      const std::lock_guard lock(mutex);
      done += n;
      png = frame;
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return cancel ? "cancelled" : "done";
  }

  render::Image mean(const std::vector<double>& sum, int samples) const {
    render::Image image(size.width, size.height);
    auto out = image.samples();
    for (std::size_t i = 0; i < sum.size(); ++i) out[i] = static_cast<float>(sum[i] / samples);
    return image;
  }

  void describe(Json& out) const override {
    out["model"] = std::string(scene.material.model.id());
    out["obj"] = mesh_name;
    out["probe"] = probe_name;
    out["estimator"] = to_string(settings.estimator);
    out["size"] = {size.width, size.height};
    out["target"] = settings.samples;
    out["samples"] = done;
    out["seconds"] = seconds;
    out["png"] = png;
  }
};

[[noreturn]] void fail(std::string_view field, const std::string& message) { throw InvalidField(std::string(field), message); }

render::RenderSettings image_size(const Fields& f, const Limits& limits) {
  const auto size = f.values_or("size", "128,128", 2);
  const double most = limits.max_environment_side;
  if (size.size() != 2 || size[0] != std::floor(size[0]) || size[1] != std::floor(size[1]) || size[0] < 8 ||
      size[1] < 8 || size[0] > most || size[1] > most)
    fail("size", fmt::format("size must be [width, height], whole numbers in [8, {}]", limits.max_environment_side));
  return {static_cast<int>(size[0]), static_cast<int>(size[1])};
}

/// The model alone: a purely specular material (ρ_s = 1, no diffuse, no ambient), as the furnace
/// renders it, so that what the view shows is the model's BRDF.
render::Scene scene_of(const Model& model, const std::shared_ptr<const Mesh>& mesh) {
  render::SceneDescription description;
  if (mesh) description.mesh = *mesh;
  description.lights.emplace();
  description.diffuse = render::Rgb{0, 0, 0};
  description.specular = render::Rgb{1, 1, 1};
  description.ambient = render::Rgb{0, 0, 0};
  return render::make_scene(model, std::move(description));
}

}  // namespace

int pass_samples(int pass, int done, int target) {
  return std::min({1 << std::min(pass, 4), 16, target - done});
}

std::shared_ptr<Job> environment_job(std::string_view body, const Limits& limits, const Uploads& uploads) {
  const Fields f(body, {"model", "params", "form", "coef", "obj", "probe", "estimator", "size", "samples", "seed", "exposure"});
  const Model model = queries::make(f.model(), Spelling::key);
  const std::string mesh_name = f.text_or("obj", "bundled");
  auto job = std::make_shared<EnvironmentJob>(scene_of(model, uploads.mesh(mesh_name, "obj")));
  job->mesh_name = mesh_name;
  job->probe_name = f.text_or("probe", "bundled");
  job->environment = uploads.probe(job->probe_name, "probe");
  job->size = image_size(f, limits);
  job->settings.samples = static_cast<int>(f.integer_or("samples", 256, 1, limits.max_environment_samples));
  job->settings.seed = static_cast<std::uint64_t>(f.integer_or("seed", 1, 0, std::int64_t{1} << 53));
  job->settings.estimator = choice_named<render::EnvironmentEstimator, render::kEnvironmentEstimatorCount>(
      "estimator", f.text_or("estimator", "mis"), Spelling::key);
  job->display.exposure = f.number_or("exposure", 0);
  if (!(std::abs(job->display.exposure) <= 20)) fail("exposure", "exposure must be in [-20, 20] stops");
  job->display.tone_map = render::ToneMap::aces;
  render::check_samples(job->size, job->settings, Spelling::key);
  render::validate(job->scene);
  job->deadline = deadline_in(limits.environment_seconds);
  return job;
}

}  // namespace specula::serve
