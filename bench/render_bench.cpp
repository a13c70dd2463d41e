// Frame times of the two renderers on the comparison scene: the default unit sphere at 1024x1024,
// log-normalized at n = 50, three lights (dir:-1,1,1, dir:1,0.5,1, point:0,3,3) — one primary ray
// per pixel, no shadow rays (one convex sphere), three lobe evaluations per lit pixel.
//
// render/cpu: render_cpu on every core oneTBB gets (the image allocation included).
// render/gl: Renderer::render in a context made once, outside the timed loop; the program is
// compiled and drawn once before the loop (`compile_ms`: GLSL compile and link, plus llvmpipe's
// LLVM compilation at the first draw), and one untimed frame makes the context's colour target,
// so an iteration is the uniform upload, the draw and the glReadPixels of the RGBA32F target
// into the image. The `renderer`
// label names the GL implementation (llvmpipe on a machine without a GPU).
// `Mpixel/s` counts pixels per second of wall time (UseRealTime: the work runs on other threads).
#include <benchmark/benchmark.h>

#include <chrono>

#include "specula/catalogue/catalogue.h"
#include "specula/gl/context.h"
#include "specula/gl/render_gl.h"
#include "specula/render/render.h"

namespace {

using namespace specula;

render::Scene comparison_scene() {
  render::Scene scene = render::default_scene(make_model("log-normalized", {{"n", 50}}));
  scene.lights = {render::Light{.direction = {-1, 1, 1}}, render::Light{.direction = {1, 0.5, 1}},
                  render::Light{.kind = render::LightKind::point, .position = {0, 3, 3}}};
  return scene;
}

void report(benchmark::State& state, int side) {
  const double pixels = static_cast<double>(side) * side;
  state.counters["Mpixel/s"] = benchmark::Counter(pixels * 1e-6 * static_cast<double>(state.iterations()),
                                                  benchmark::Counter::kIsRate);
}

void BM_RenderCpu(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const render::Scene scene = comparison_scene();
  for (auto _ : state) benchmark::DoNotOptimize(render::render_cpu(scene, {side, side}));
  report(state, side);
}
BENCHMARK(BM_RenderCpu)->Name("render/cpu")->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_RenderGl(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const render::Scene scene = comparison_scene();
  const gl::Context context;
  gl::Renderer renderer(context);
  const auto start = std::chrono::steady_clock::now();
  renderer.prepare(scene.material.model, render::geometry_of(scene));
  renderer.render(scene, {1, 1});  // llvmpipe turns the shader into machine code at its first draw
  const double compile_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  renderer.render(scene, {side, side});  // the context's colour target at this size, made once
  for (auto _ : state) benchmark::DoNotOptimize(renderer.render(scene, {side, side}));
  report(state, side);
  state.counters["compile_ms"] = compile_ms;
  state.SetLabel(context.info().renderer);
}
BENCHMARK(BM_RenderGl)->Name("render/gl")->Arg(1024)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
