// Renderer throughput with and without the SIMD batch shading path (RenderSettings::batch_shading):
// the comparison sphere (render::default_scene: one sphere, no shadow rays) lit by three lights
// (two directional, one point), 512 × 512, one thread (tbb::global_control), shaded with each
// model family. t_per_pixel = time per pixel.
//   render/<model>/<per_pixel|batch>
#include <benchmark/benchmark.h>

#include <string>
#include <tbb/global_control.h>

#include "specula/catalogue/catalogue.h"
#include "specula/render/render.h"
#include "specula/render/scene.h"

namespace {

using namespace specula;

void bm_render(benchmark::State& state, const char* id, bool batch) {
  render::Scene scene = render::default_scene(make_model(id, id == std::string("ggx") ? ParamValues{} : ParamValues{{"n", 50}}));
  scene.lights = {{render::LightKind::directional, {1, 1, 2}, {}, {1, 1, 1}, 1},
                  {render::LightKind::directional, {-1, 0.5, 1}, {}, {0.8, 0.9, 1}, 0.5},
                  {render::LightKind::point, {}, {-3, 2, 4}, {1, 0.9, 0.8}, 30}};
  const render::RenderSettings settings{512, 512, batch};
  const tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
  for (auto _ : state) {
    render::Image image = render::render_cpu(scene, settings);
    benchmark::DoNotOptimize(image);
  }
  state.counters["t_per_pixel"] = benchmark::Counter(512.0 * 512.0, benchmark::Counter::kIsIterationInvariantRate |
                                                                         benchmark::Counter::kInvert);
}

[[maybe_unused]] const bool registered = [] {
  for (const char* id : {"phong-normalized", "log-normalized", "schlick-normalized", "gauss", "ggx"})
    for (const bool batch : {false, true})
      benchmark::RegisterBenchmark((std::string("render/") + id + (batch ? "/batch" : "/per_pixel")).c_str(),
                                   bm_render, id, batch)
          ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
