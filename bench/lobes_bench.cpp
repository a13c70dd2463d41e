// Lobe evaluation throughput: ns per F(c) for every lobe family, float and double, through
// the struct (inline, the renderer's path), the run-time `Lobe` variant (per batch and per
// value) and a registry Model (`make_model("log-normalized")`, per value).
//
// Input: kCount = 4096 cosines (16 KiB as float, 32 KiB as double; in + out stay in L1/L2),
// reused every iteration. Distribution ("peaked", the default): θ = (π/2)·x², x stratified on
// (0, 1), c = cos θ, then shuffled with a fixed seed so that the order gives the branch
// predictor nothing. Half of the cosines exceed cos 22.5° ≈ 0.924 and 10 % exceed cos 0.9°,
// i.e. most samples sit near the peak, as in shading where the specular lobe is evaluated
// around the highlight (importance-sampled or near-mirror directions); none is ≤ 0 or = 1, so
// the clamp never fires. For the log lobe at n = 20 (cutoff c₀ = 2^(−3/20) ≈ 0.901, 25.7°)
// about 53 % of the cosines are inside the support; at n = 1000 (c₀ ≈ 0.9979, 3.7°) about 20 %.
// A "uniform" distribution (c stratified on (0, 1), shuffled) is added for n = 20, double, to
// show how much the argument distribution matters to libm (pow, log2, acos have fast paths;
// pow takes a slow path where c^n underflows, which is why power/n:1000 costs more than n:20).
//
// Paths: lobe/<family>/<type>/n:N is the struct, inlined; lobe/variant_batch/… is eval_batch on
// a `Lobe` (one dispatch per batch); lobe/variant_eval/… calls lobes::eval(Lobe, c) per value,
// but GCC hoists that visit out of the loop (the variant is loop-invariant), so it costs the same
// as the batch; lobe/variant_eval_opaque/… forces a dispatch per value. model/at_cos/… is
// Model::at_cos per value (std::get check + visit + the multiplication by k).
//
// Each reported `t_per_eval` counter is CPU time per evaluation (shown with an SI prefix: "n" =
// ns); items_per_second is its inverse.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstddef>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "specula/lobes/lobes.h"
#include "specula/catalogue/catalogue.h"

namespace {

using namespace specula;

constexpr std::size_t kCount = 4096;

enum class Dist { peaked, uniform };

template <class T>
std::vector<T> make_cosines(Dist dist) {
  std::vector<T> c(kCount);
  for (std::size_t i = 0; i < kCount; ++i) {
    const double x = (static_cast<double>(i) + 0.5) / static_cast<double>(kCount);
    c[i] = static_cast<T>(dist == Dist::peaked ? std::cos(std::numbers::pi / 2 * x * x) : x);
  }
  std::mt19937 rng(20231105u);
  std::shuffle(c.begin(), c.end(), rng);
  return c;
}

template <class T>
const std::vector<T>& cosines(Dist dist) {
  static const std::vector<T> peaked = make_cosines<T>(Dist::peaked);
  static const std::vector<T> uniform = make_cosines<T>(Dist::uniform);
  return dist == Dist::peaked ? peaked : uniform;
}

void set_per_eval(benchmark::State& state) {
  const auto evals = static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(kCount);
  state.SetItemsProcessed(evals);
  state.counters["t_per_eval"] = benchmark::Counter(
      static_cast<double>(kCount),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// The struct path: out[i] = lobe(c[i]), the call inlined as in a renderer's loop.
template <class L>
void bm_struct(benchmark::State& state, L lobe, Dist dist) {
  using T = decltype(lobe.n);
  const std::vector<T>& in = cosines<T>(dist);
  std::vector<T> out(in.size());
  benchmark::DoNotOptimize(lobe);
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.data());  // in[] escapes: the clobber below may rewrite it
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = lobe(in[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();  // out[] must be written every iteration
  }
  set_per_eval(state);
}

/// The run-time path, one dispatch per batch: lobes::eval_batch(const Lobe&, span, span).
void bm_variant_batch(benchmark::State& state, lobes::Lobe lobe) {
  const std::vector<double>& in = cosines<double>(Dist::peaked);
  std::vector<double> out(in.size());
  benchmark::DoNotOptimize(lobe);
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.data());
    lobes::eval_batch(lobe, std::span<const double>(in), std::span<double>(out));
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_eval(state);
}

/// The run-time path, one dispatch per value: lobes::eval(const Lobe&, double).
void bm_variant_eval(benchmark::State& state, lobes::Lobe lobe) {
  const std::vector<double>& in = cosines<double>(Dist::peaked);
  std::vector<double> out(in.size());
  benchmark::DoNotOptimize(lobe);
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.data());
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = lobes::eval(lobe, in[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_eval(state);
}

/// As bm_variant_eval, but the lobe is re-read through an opaque pointer for every value, so the
/// compiler cannot hoist the visit out of the loop (GCC does so in bm_variant_eval): the cost
/// of a real per-value dispatch, as when the lobe can change from one value to the next.
void bm_variant_eval_opaque(benchmark::State& state, lobes::Lobe lobe) {
  const std::vector<double>& in = cosines<double>(Dist::peaked);
  std::vector<double> out(in.size());
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.data());
    for (std::size_t i = 0; i < in.size(); ++i) {
      const lobes::Lobe* opaque = &lobe;
      benchmark::DoNotOptimize(opaque);
      out[i] = lobes::eval(*opaque, in[i]);
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_eval(state);
}

/// A registry model, k·F(c) per value: Model::at_cos.
void bm_model_at_cos(benchmark::State& state, const char* id, double n) {
  const Model model = make_model(id, {{"n", n}});
  const std::vector<double>& in = cosines<double>(Dist::peaked);
  std::vector<double> out(in.size());
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.data());
    for (std::size_t i = 0; i < in.size(); ++i) out[i] = model.at_cos(in[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  set_per_eval(state);
}

/// Building a model through the registry (lookup, parameter checks, k = log_rv(n)).
void bm_make_model(benchmark::State& state, const char* id, double n) {
  const ParamValues params{{"n", n}};
  for (auto _ : state) {
    Model model = make_model(id, params);
    benchmark::DoNotOptimize(model);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

std::string n_label(int n) { return "n:" + std::to_string(n); }

template <template <class> class L>
void register_family(const char* family, std::initializer_list<int> ns) {
  for (const int n : ns) {
    benchmark::RegisterBenchmark(
        (std::string("lobe/") + family + "/float/" + n_label(n)).c_str(), bm_struct<L<float>>,
        L<float>{static_cast<float>(n)}, Dist::peaked);
    benchmark::RegisterBenchmark(
        (std::string("lobe/") + family + "/double/" + n_label(n)).c_str(), bm_struct<L<double>>,
        L<double>{static_cast<double>(n)}, Dist::peaked);
  }
  benchmark::RegisterBenchmark(
      (std::string("lobe/") + family + "/double/n:20/dist:uniform").c_str(),
      bm_struct<L<double>>, L<double>{20.0}, Dist::uniform);
  benchmark::RegisterBenchmark(
      (std::string("lobe/variant_batch/") + family + "/double/n:20").c_str(), bm_variant_batch,
      lobes::Lobe{L<double>{20.0}});
  benchmark::RegisterBenchmark(
      (std::string("lobe/variant_eval/") + family + "/double/n:20").c_str(), bm_variant_eval,
      lobes::Lobe{L<double>{20.0}});
  benchmark::RegisterBenchmark(
      (std::string("lobe/variant_eval_opaque/") + family + "/double/n:20").c_str(),
      bm_variant_eval_opaque, lobes::Lobe{L<double>{20.0}});
}

[[maybe_unused]] const bool registered = [] {
  register_family<lobes::Power>("power", {20, 1000});
  register_family<lobes::Schlick>("schlick", {20});
  register_family<lobes::SchlickModified>("schlick-modified", {20});
  register_family<lobes::Gauss>("gauss", {20});
  register_family<lobes::Log>("log", {20, 1000});
  for (const int n : {20, 1000}) {
    benchmark::RegisterBenchmark(("model/at_cos/log-normalized/double/" + n_label(n)).c_str(),
                                 bm_model_at_cos, "log-normalized", static_cast<double>(n));
  }
  benchmark::RegisterBenchmark("model/make_model/log-normalized/n:20", bm_make_model,
                               "log-normalized", 20.0);
  return true;
}();

}  // namespace
