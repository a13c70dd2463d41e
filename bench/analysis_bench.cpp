// Analysis cost: directional albedo by cubature (per albedo, and the 91 × 1000 grid),
// the approximation-error sweep over n, Monte-Carlo albedo throughput and the energy check's
// max_albedo search.
//
// Sweeps run on oneTBB (analysis::parallel_map, analysis::albedo_curve), so the benchmarks that
// use it report wall-clock time (UseRealTime): CPU time would count only the main thread. The
// multi-second ones run once (Iterations(1)); a shared machine makes any single run noisy, and
// nothing here asserts on time.
//
//   analysis/albedo/<model>/<param>/theta:D
//       one analysis::albedo call at θ_i = D degrees, single-threaded; t_per_albedo = CPU time.
//   analysis/albedo_grid/log-normalized/theta:91/n:1:1000/{parallel_n,curve_per_n}
//       the target (< 10 s on 2 cores): ρ at θ_i = 0, 1, …, 89 and 89.5° (91 angles) for
//       n = 1, 2, …, 1000 (91 000 albedos). parallel_n: analysis::parallel_map over n, each task
//       computing its 91 angles in turn; curve_per_n: n in turn, analysis::albedo_curve (parallel
//       over the 91 angles) for each. make_model per n (the exact k) is inside the timing.
//   analysis/error_sweep/<model>_vs_phong/n:1:1000, analysis/error_sweep/all3_vs_phong/n:1:1000
//       the second target (< 1 s for the three): analysis::approximation_error of the bare
//       log, schlick and schlick-modified (s = 1.25) lobes against phong (zone ½), parallel_map
//       over n = 1, 2, …, 1000 — what `specula error --n 1:1000` computes, without the table.
//   analysis/albedo_monte_carlo/<model>/<param>/theta:45/samples:100000[/scalar_target]
//       analysis::albedo_monte_carlo, single-threaded; items_per_second = samples per second.
//       scalar_target: the same on Highway's scalar target (its BRDF batches one lane at a
//       time), so that the SIMD gain is the ratio of the two rates in one run.
//   analysis/max_albedo/log-normalized/n:20/step:1
//       analysis::max_albedo (the check's search): albedo_curve over 0:89 + 89.5 + 89.9°, then
//       golden-section refinement to 1e-4°.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "specula/analysis/albedo.h"
#include "specula/analysis/check.h"
#include "specula/analysis/error.h"
#include "specula/analysis/monte_carlo.h"
#include "specula/simd/targets.h"
#include "specula/analysis/parallel.h"
#include "specula/brdf/directions.h"
#include "specula/lobes/lobes.h"
#include "specula/catalogue/catalogue.h"

namespace {

using namespace specula;

void set_per_item(benchmark::State& state, const char* counter, std::size_t items_per_iteration) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(items_per_iteration));
  state.counters[counter] = benchmark::Counter(
      static_cast<double>(items_per_iteration),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

std::vector<double> n_range(int last) {
  std::vector<double> ns(static_cast<std::size_t>(last));
  std::iota(ns.begin(), ns.end(), 1.0);
  return ns;
}

/// θ_i = 0, 1, …, 89 and 89.5 degrees, in radians.
std::vector<double> grid_angles() {
  std::vector<double> theta;
  for (int d = 0; d < 90; ++d) theta.push_back(radians(static_cast<double>(d)));
  theta.push_back(radians(89.5));
  return theta;
}

// ---- 1. Cubature albedo ----------------------------------------------------------------------

void bm_albedo(benchmark::State& state, Model model, double theta_deg) {
  const double theta = radians(theta_deg);
  for (auto _ : state) {
    benchmark::DoNotOptimize(model);
    auto a = analysis::albedo(model, theta);
    benchmark::DoNotOptimize(a);
  }
  set_per_item(state, "t_per_albedo", 1);
}

Model log_normalized(double n) { return make_model("log-normalized", {{"n", n}}); }

void bm_grid_parallel_n(benchmark::State& state) {
  const std::vector<double> theta = grid_angles(), ns = n_range(1000);
  for (auto _ : state) {
    const auto rows = analysis::parallel_map(std::span<const double>(ns), [&](double n) {
      const Model m = log_normalized(n);
      std::vector<double> row(theta.size());
      for (std::size_t i = 0; i < theta.size(); ++i) row[i] = analysis::albedo(m, theta[i]).value;
      return row;
    });
    benchmark::DoNotOptimize(rows.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, "t_per_albedo", theta.size() * ns.size());
}

void bm_grid_curve_per_n(benchmark::State& state) {
  const std::vector<double> theta = grid_angles(), ns = n_range(1000);
  for (auto _ : state) {
    std::vector<std::vector<double>> rows;
    rows.reserve(ns.size());
    for (const double n : ns) rows.push_back(analysis::albedo_curve(log_normalized(n), theta));
    benchmark::DoNotOptimize(rows.data());
    benchmark::ClobberMemory();
  }
  set_per_item(state, "t_per_albedo", theta.size() * ns.size());
}

// ---- 2. Approximation-error sweep ------------------------------------------------------------

using LobeOf = lobes::Lobe (*)(double n);

lobes::Lobe log_lobe(double n) { return lobes::Log<>{n}; }
lobes::Lobe schlick_lobe(double n) { return lobes::Schlick<>{n}; }
lobes::Lobe schlick_modified_lobe(double n) { return lobes::SchlickModified<>{n, 1.25}; }

void bm_error_sweep(benchmark::State& state, std::vector<LobeOf> models) {
  const std::vector<double> ns = n_range(1000);
  for (auto _ : state) {
    for (const LobeOf model : models) {
      const auto errors = analysis::parallel_map(std::span<const double>(ns), [&](double n) {
        return analysis::approximation_error(model(n), lobes::Power<>{n});
      });
      benchmark::DoNotOptimize(errors.data());
      benchmark::ClobberMemory();
    }
  }
  set_per_item(state, "t_per_error", ns.size() * models.size());
}

// ---- 3. Monte-Carlo albedo -------------------------------------------------------------------

constexpr std::size_t kSamples = 100'000;

void bm_monte_carlo(benchmark::State& state, Model model, bool scalar_target) {
  std::optional<simd::ScopedTarget> scalar;
  if (scalar_target) scalar.emplace(simd::runnable_targets().back());
  const double theta = radians(45.0);
  std::uint64_t seed = 1;
  for (auto _ : state) {
    benchmark::DoNotOptimize(model);
    auto e = analysis::albedo_monte_carlo(model, theta, kSamples, seed++);
    benchmark::DoNotOptimize(e);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(kSamples));
}

// ---- 4. max_albedo ---------------------------------------------------------------------------

void bm_max_albedo(benchmark::State& state, Model model, double step_deg) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(model);
    auto m = analysis::max_albedo(model, step_deg);
    benchmark::DoNotOptimize(m);
  }
}

struct Case {
  const char* label;  ///< "<model>/<param>:<value>"
  const char* id;
  const char* param;
  double value;
};

[[maybe_unused]] const bool registered = [] {
  const Case albedo_cases[] = {
      {"log-normalized/n:20", "log-normalized", "n", 20},
      {"log-normalized/n:1000", "log-normalized", "n", 1000},
      {"blinn-phong-normalized/n:20", "blinn-phong-normalized", "n", 20},
      {"blinn-phong-normalized/n:1e4", "blinn-phong-normalized", "n", 1e4},
      {"ward/alpha:0.2", "ward", "alpha", 0.2},
      {"ggx/alpha:0.3", "ggx", "alpha", 0.3},
      {"cook-torrance/m:0.3", "cook-torrance", "m", 0.3},
  };
  for (const Case& c : albedo_cases)
    benchmark::RegisterBenchmark((std::string("analysis/albedo/") + c.label + "/theta:45").c_str(),
                                 bm_albedo, make_model(c.id, {{c.param, c.value}}), 45.0)
        ->Unit(benchmark::kMicrosecond);
  for (const Case& c : {albedo_cases[0], albedo_cases[5]})
    benchmark::RegisterBenchmark((std::string("analysis/albedo/") + c.label + "/theta:89.5").c_str(),
                                 bm_albedo, make_model(c.id, {{c.param, c.value}}), 89.5)
        ->Unit(benchmark::kMicrosecond);

  benchmark::RegisterBenchmark("analysis/albedo_grid/log-normalized/theta:91/n:1:1000/parallel_n",
                               bm_grid_parallel_n)
      ->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);
  benchmark::RegisterBenchmark("analysis/albedo_grid/log-normalized/theta:91/n:1:1000/curve_per_n",
                               bm_grid_curve_per_n)
      ->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

  benchmark::RegisterBenchmark("analysis/error_sweep/log_vs_phong/n:1:1000", bm_error_sweep,
                               std::vector<LobeOf>{log_lobe})
      ->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("analysis/error_sweep/schlick_vs_phong/n:1:1000", bm_error_sweep,
                               std::vector<LobeOf>{schlick_lobe})
      ->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("analysis/error_sweep/schlick-modified_vs_phong/n:1:1000",
                               bm_error_sweep, std::vector<LobeOf>{schlick_modified_lobe})
      ->Unit(benchmark::kMillisecond)->UseRealTime();
  benchmark::RegisterBenchmark("analysis/error_sweep/all3_vs_phong/n:1:1000", bm_error_sweep,
                               std::vector<LobeOf>{log_lobe, schlick_lobe, schlick_modified_lobe})
      ->Unit(benchmark::kMillisecond)->UseRealTime();

  for (const bool scalar_target : {false, true}) {
    const std::string suffix = scalar_target ? "/scalar_target" : "";
    benchmark::RegisterBenchmark(("analysis/albedo_monte_carlo/ggx/alpha:0.3/theta:45/samples:100000" + suffix).c_str(),
                                 bm_monte_carlo, make_model("ggx", {{"alpha", 0.3}}), scalar_target)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("analysis/albedo_monte_carlo/log-normalized/n:20/theta:45/samples:100000" + suffix).c_str(),
                                 bm_monte_carlo, log_normalized(20), scalar_target)
        ->Unit(benchmark::kMillisecond);
  }

  benchmark::RegisterBenchmark("analysis/max_albedo/log-normalized/n:20/step:1", bm_max_albedo,
                               log_normalized(20), 1.0)
      ->Unit(benchmark::kMillisecond)->UseRealTime();
  return true;
}();

}  // namespace
