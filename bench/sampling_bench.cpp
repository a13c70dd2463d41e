// Importance sampling throughput beside evaluation, per model at its default parameters, one
// thread (sampling/sampler.h):
//
//   sampling/eval/<model>     f(N, L, V) alone (Model::operator()), at the directions the sampler
//                             draws; items_per_second = evaluations per second
//   sampling/sample/<model>   Sampler::sample (a direction, its pdf, f and the weight);
//                             items_per_second = samples per second per core
//   sampling/pdf/<model>      Sampler::pdf at the same directions
//
// θ_i = 45°; the uniform numbers are drawn before the timing. Measurements, never assertions.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "specula/catalogue/catalogue.h"
#include "specula/sampling/sampler.h"

namespace {

using namespace specula;

constexpr std::size_t kBatch = 4096;
const Vec3 kNormal{0, 0, 1};
const Vec3 kLight{std::sqrt(0.5), 0, std::sqrt(0.5)};

std::vector<double> uniforms() {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> values(2 * kBatch);
  for (double& v : values) v = u(rng);
  return values;
}

std::vector<Vec3> sampled_directions(const sampling::Sampler& sampler, const std::vector<double>& u) {
  std::vector<Vec3> directions;
  for (std::size_t i = 0; i < kBatch; ++i) {
    const sampling::Sample s = sampler.sample(kLight, u[2 * i], u[2 * i + 1]);
    directions.push_back(s.valid() ? s.wo : kNormal);
  }
  return directions;
}

void bench_sample(benchmark::State& state, const std::string& id) {
  const sampling::Sampler sampler(make_model(id));
  const std::vector<double> u = uniforms();
  for (auto _ : state)
    for (std::size_t i = 0; i < kBatch; ++i) benchmark::DoNotOptimize(sampler.sample(kLight, u[2 * i], u[2 * i + 1]));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kBatch));
}

void bench_pdf(benchmark::State& state, const std::string& id) {
  const sampling::Sampler sampler(make_model(id));
  const std::vector<Vec3> wo = sampled_directions(sampler, uniforms());
  for (auto _ : state)
    for (const Vec3& v : wo) benchmark::DoNotOptimize(sampler.pdf(kLight, v));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kBatch));
}

void bench_eval(benchmark::State& state, const std::string& id) {
  const Model model = make_model(id);
  const std::vector<Vec3> wo = sampled_directions(sampling::Sampler(model), uniforms());
  for (auto _ : state)
    for (const Vec3& v : wo) benchmark::DoNotOptimize(model(kNormal, kLight, v));
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(kBatch));
}

const bool registered = [] {
  for (const ModelInfo& info : models()) {
    benchmark::RegisterBenchmark(("sampling/eval/" + info.id).c_str(), bench_eval, info.id);
    benchmark::RegisterBenchmark(("sampling/sample/" + info.id).c_str(), bench_sample, info.id);
    benchmark::RegisterBenchmark(("sampling/pdf/" + info.id).c_str(), bench_pdf, info.id);
  }
  return true;
}();

}  // namespace
