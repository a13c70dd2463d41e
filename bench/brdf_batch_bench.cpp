// Whole models over arrays of directions through the SIMD batch path (simd/brdf.h), the C++ side of
// bench/python_bench.py's BRDF column: 2^20 random (N = +z, L, V) triples above the horizon, held
// as structure of arrays, one thread. t_per_eval = time per evaluation.
//   brdf_batch/<model>/<exact|fast>
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "specula/catalogue/catalogue.h"
#include "specula/simd/brdf.h"

namespace {

using namespace specula;

constexpr std::size_t kCount = std::size_t{1} << 20;

/// Unit directions uniform over the upper hemisphere, as three columns.
std::vector<std::vector<double>> hemisphere(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::vector<double>> xyz(3, std::vector<double>(kCount));
  for (std::size_t i = 0; i < kCount; ++i) {
    const double z = u(rng), phi = 2 * std::numbers::pi * u(rng), r = std::sqrt(1 - z * z);
    xyz[0][i] = r * std::cos(phi), xyz[1][i] = r * std::sin(phi), xyz[2][i] = z;
  }
  return xyz;
}

void bm_brdf_batch(benchmark::State& state, const char* id, simd::Tier tier) {
  std::mt19937_64 rng(1);
  const auto l = hemisphere(rng), v = hemisphere(rng);
  const std::vector<double> zero(kCount, 0.0), one(kCount, 1.0);
  const simd::DirectionBatch dirs{zero, zero, one, l[0], l[1], l[2], v[0], v[1], v[2]};
  const Model model = make_model(id, {});
  std::vector<double> out(kCount);
  for (auto _ : state) {
    simd::eval_batch(model, tier, dirs, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["t_per_eval"] = benchmark::Counter(static_cast<double>(kCount),
                                                    benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

[[maybe_unused]] const bool registered = [] {
  for (const char* id : {"ggx", "ward", "cook-torrance", "lambert", "log-normalized", "phong-normalized"})
    for (const simd::Tier tier : {simd::Tier::exact, simd::Tier::fast})
      benchmark::RegisterBenchmark((std::string("brdf_batch/") + id + "/" + to_string(tier)).c_str(), bm_brdf_batch, id,
                                   tier)
          ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace
