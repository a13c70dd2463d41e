// specula render: an image of a sphere or an OBJ mesh shaded with a model (the paper's Figs. 10-11).
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <iostream>
#include <optional>
#include <vector>
#include <tbb/info.h>

#include "cli.h"
#include "scene_options.h"
#include "specula/exceptions.h"
#include "specula/gl/render_gl.h"
#include "specula/render/environment.h"
#include "specula/render/image_io.h"
#include "specula/render/render.h"

namespace specula::cli {
namespace {

struct RenderOptions {
  ModelOptions model;
  SceneOptions scene;  ///< --scene, --size, --light, the colours, --exposure, --tonemap
  std::string exr_pixel = "half";
  std::string backend = "cpu";
  std::string env;  ///< empty: lit by the lights; "white" or an image file
  int samples = 64;
  std::uint64_t seed = 0;
  std::string estimator = "mis";
  std::string out;
  bool verbose = false;
};

render::Scene scene_of(const RenderOptions& o) {
  const Model model = o.model.make();
  render::SceneDescription d = o.scene.description();
  if (!o.env.empty() && !d.lights) d.lights.emplace();  // the environment is the only light
  if (o.env == "white") {
    // The white furnace shows the bare model: specular 1, no diffuse or ambient term.
    d.diffuse = d.diffuse.value_or(render::Rgb{0, 0, 0});
    d.specular = d.specular.value_or(render::Rgb{1, 1, 1});
    d.ambient = d.ambient.value_or(render::Rgb{0, 0, 0});
  }
  return render::make_scene(model, std::move(d));
}

// What rendered the image: "cpu", or the GL renderer's description (render_gl).
struct Rendered {
  render::Image image;
  std::string gl_renderer;  ///< empty for the CPU backend
};

render::Metadata metadata_of(const render::Scene& scene, const RenderOptions& o, const Rendered& rendered,
                             bool with_display) {
  const Model& model = scene.material.model;
  std::vector<std::string> params;
  for (std::size_t i = 0; i < model.params().size(); ++i)
    params.push_back(fmt::format("{}={}", model.info().params[i].name, io::format_number(model.params()[i])));
  const std::string parameters = o.model.per_channel() ? fmt::format("{}", fmt::join(o.model.params, "; "))  // NAME=R,G,B
                                                       : fmt::format("{}", fmt::join(params, ","));
  render::Metadata meta{{"Software", "specula"},
                        {"model", std::string(model.id())},
                        {"parameters", parameters},
                        {"form", model.is_lobe() ? to_string(model.form()) : "-"}};
  if (model.is_lobe()) meta.emplace_back("coef", io::format_number(model.coef()));
  meta.insert(meta.end(), {{"renderer", o.backend}, {"scene", o.scene.mesh}, {"size", o.scene.size}});
  const render::Metadata lit = scene_metadata(scene);
  meta.insert(meta.end(), lit.begin(), lit.end());
  if (!o.env.empty())
    meta.insert(meta.end(), {{"environment", o.env}, {"samples", std::to_string(o.samples)}, {"seed", std::to_string(o.seed)},
                                {"estimator", o.estimator}});
  if (!rendered.gl_renderer.empty()) meta.emplace_back("gl-renderer", rendered.gl_renderer);
  if (with_display)
    meta.insert(meta.end(), {{"exposure", io::format_number(o.scene.exposure)}, {"tonemap", o.scene.tone_map}});
  return meta;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// With --env: the uniform white furnace or the probe of the file; none without.
std::optional<render::Environment> environment_of(const RenderOptions& o, render::Backend backend,
                                                  const render::RenderSettings& settings) {
  if (o.env.empty()) return std::nullopt;
  if (!o.scene.lights.empty()) throw InvalidArgument("--light cannot be combined with --env: the environment is the only light");
  if (backend != render::Backend::cpu) throw InvalidArgument("--env renders on the cpu backend only");
  render::check_samples(settings, {o.samples, o.seed}, Spelling::option);
  if (o.env == "white") return render::Environment::uniform({1, 1, 1});
  return render::read_environment(o.env);
}

Rendered render_on_backend(const RenderOptions& o, render::Backend backend, const render::Scene& scene,
                           const std::optional<render::Environment>& environment,
                           const render::RenderSettings& settings) {
  if (environment) {
    const auto estimator = choice_named<render::EnvironmentEstimator, render::kEnvironmentEstimatorCount>(
        "estimator", o.estimator, Spelling::option);
    return {render::render_environment(scene, *environment, settings, {o.samples, o.seed, estimator}), ""};
  }
  if (backend == render::Backend::cpu) return {render::render_cpu(scene, settings), ""};
  const gl::Context context;
  gl::Renderer renderer(context);
  return {renderer.render(scene, settings), gl::to_string(context.info())};
}

std::string backend_text(const Rendered& rendered) {
  if (rendered.gl_renderer.empty()) return fmt::format("on {} threads", tbb::info::default_concurrency());
  return "on GL " + rendered.gl_renderer;
}

std::string lighting_text(const RenderOptions& o, const render::Scene& scene) {
  if (!o.env.empty()) return fmt::format("environment {}, {} samples per pixel", o.env, o.samples);
  return fmt::format("{} light{}", scene.lights.size(), scene.lights.size() == 1 ? "" : "s");
}

/// A scene and its image.
struct SceneRender {
  render::Scene scene;
  Rendered rendered;
};

SceneRender render_one(const RenderOptions& o, render::Backend backend,
                       const std::optional<render::Environment>& environment, const render::RenderSettings& settings) {
  render::Scene scene = scene_of(o);
  Rendered rendered = render_on_backend(o, backend, scene, environment, settings);
  return {std::move(scene), std::move(rendered)};
}

/// A coloured material (ModelOptions::per_channel): the three channels' scenes first (a value out
/// of range is refused before any render), then one render per channel, each giving its channel of
/// the image; the scene of channel 0 stands for the rest.
SceneRender render_per_channel(const RenderOptions& o, render::Backend backend,
                               const std::optional<render::Environment>& environment,
                               const render::RenderSettings& settings) {
  std::vector<RenderOptions> channels(3, o);
  std::vector<render::Scene> scenes;
  for (int c = 0; c < 3; ++c) {
    channels[c].model = o.model.channel(c);
    scenes.push_back(scene_of(channels[c]));
  }
  Rendered image = render_on_backend(channels[0], backend, scenes[0], environment, settings);
  for (int c = 1; c < 3; ++c) {  // G and B replaced by their channels' renders
    const Rendered channel = render_on_backend(channels[c], backend, scenes[c], environment, settings);
    auto to = image.image.samples();
    const auto from = channel.image.samples();
    for (std::size_t k = static_cast<std::size_t>(c); k < to.size(); k += 3) to[k] = from[k];
  }
  return {std::move(scenes[0]), std::move(image)};
}

void run_render(const RenderOptions& o) {
  const render::ImageFormat format = render::image_format(o.out);
  const render::Display display = o.scene.display();
  if (format == render::ImageFormat::exr && (display.exposure != 0 || display.tone_map != render::ToneMap::none))
    throw InvalidArgument("--exposure and --tonemap shape 8-bit output; an EXR holds the linear radiance as rendered");
  const render::ExrPixel exr_pixel = parse_exr_pixel(o.exr_pixel);
  const render::Backend backend = parse_backend(o.backend);
  const render::RenderSettings settings = o.scene.settings();
  const std::optional<render::Environment> environment = environment_of(o, backend, settings);

  const auto start = std::chrono::steady_clock::now();
  const SceneRender done = o.model.per_channel() ? render_per_channel(o, backend, environment, settings)
                                                 : render_one(o, backend, environment, settings);
  const render::Scene& scene = done.scene;
  const Rendered& rendered = done.rendered;
  const double render_ms = milliseconds_since(start);
  const auto written = std::chrono::steady_clock::now();
  if (format == render::ImageFormat::png)
    render::write_png(o.out, rendered.image, display, metadata_of(scene, o, rendered, true));
  else
    render::write_exr(o.out, rendered.image, exr_pixel, metadata_of(scene, o, rendered, false));
  if (o.verbose)
    std::cerr << fmt::format("specula: rendered {}x{} ({}) in {:.1f} ms {}; wrote {} in {:.1f} ms\n", settings.width,
                             settings.height, lighting_text(o, scene), render_ms, backend_text(rendered), o.out,
                             milliseconds_since(written));
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  auto* cmd = app.add_subcommand("render", "Render a sphere or an OBJ mesh shaded with a model");
  o->model.add_to(*cmd);
  cmd->get_option("--param")->description(
      "Parameter as NAME=VALUE, repeatable; NAME=R,G,B gives a coloured material, one model per channel\n"
      "(-p eta=0.143,0.374,1.442 -p kappa=3.98,2.38,1.60: gold as ggx-conductor)");
  o->model.add_coef_to(*cmd);
  o->scene.add_to(*cmd, Picture::render);
  cmd->add_option("--exr-pixel", o->exr_pixel, "EXR samples: half or float")->capture_default_str()
      ->check(one_of<render::ExrPixel, render::kExrPixelCount>());
  cmd->add_option("--backend", o->backend,
                  "cpu, or gl: OpenGL 3.3 through EGL (a GPU if EGL lists one, else Mesa's llvmpipe);\n"
                  "the same image within float rounding; at most 16 spheres and 8 lights")->capture_default_str()
      ->check(one_of<render::Backend, render::kBackendCount>());
  auto* env = cmd->add_option("--env", o->env,
                  "Light the scene by an environment alone (docs/render.md): white (radiance 1 from everywhere:\n"
                  "the white furnace; the material defaults to specular 1, no diffuse, no ambient) or a\n"
                  "latitude-longitude FILE.exr or FILE.png (row 0 up +y, the centre column toward -z); no --light");
  cmd->add_option("--samples", o->samples,
                  "With --env: sample pairs per pixel (with mis, one BRDF + one environment sample),\n"
                  "[1, 65536], at most 2^26 in the image (1024x1024 at 64; about a minute)")->capture_default_str()->needs(env);
  cmd->add_option("--seed", o->seed, "With --env: the same seed gives the same image, whatever the thread count")
      ->capture_default_str()->needs(env);
  cmd->add_option("--estimator", o->estimator,
                  "With --env: how each pixel's integral is sampled, two directions per sample: uniform (no\n"
                  "importance sampling), environment (light sampling), brdf (the model's sampler) or mis (one of\n"
                  "each, power heuristic); all unbiased, they differ in noise")
      ->capture_default_str()->needs(env)->check(one_of<render::EnvironmentEstimator, render::kEnvironmentEstimatorCount>());
  cmd->add_option("--out,-o", o->out, "Output image: FILE.png (8-bit sRGB) or FILE.exr (linear)")->required();
  cmd->add_flag("--verbose,-v", o->verbose, "Print the render and write times (and the GL renderer) to stderr");
  cmd->footer(
      "Shading (docs/math.md §5): L = ambient·diffuse + Σ_lights (diffuse/π + specular·f(N, L, V))·E·max(0, N·L),\n"
      "one ray per pixel centre; OBJ meshes cast shadows. PNG and EXR carry the model, its parameters,\n"
      "form and the render settings as text metadata. Examples:\n"
      "  specula render --model log-normalized -p n=50 --out sphere.png\n"
      "  specula render --model phong-normalized -p n=20 --size 800x600 --light dir:1,1,2 \\\n"
      "      --light point:-3,2,4:1,0.9,0.8:30 --tonemap aces --out sphere.png\n"
      "  specula render --model ggx -p alpha=0.2 --scene bunny.obj --exr-pixel float --out bunny.exr\n"
      "  specula render --model log-normalized -p n=50 --backend gl --size 2048x2048 --verbose --out big.png\n"
      "  specula render --model ggx --env white --out furnace.exr\n"
      "  specula render --model ggx-conductor -p alpha=0.3 -p eta=0.143,0.374,1.442 -p kappa=3.98,2.38,1.60 \\\n"
      "      --env white --out gold.png                     # a metal: one model per channel\n"
      "  specula render --model ggx -p alpha=0.2 --env probe.exr --samples 256 --seed 7 --out ggx.exr");
  cmd->callback([o] { run_render(*o); });
}

}  // namespace specula::cli
