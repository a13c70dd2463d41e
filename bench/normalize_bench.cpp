// Normalization cost per n: the closed forms (ns per call) and quadrature (µs per call).
//
// lobes::log_rv takes different branches with a = 2 ln 2/n: the series in a for a ≤ 1
// (n ≥ 2 ln 2 ≈ 1.386; slowest to converge near a = 1, fastest for huge n), and e^x E₁(x) for
// a > 1, by Boost's expint for x ≤ 50 and by an asymptotic series beyond (n ≲ 0.11 for 4a,
// n ≲ 0.028 for a). The single-n benchmarks pin one branch each; `paper50` is the mix a table
// of io::paper50() costs (items = 50 values, so items_per_second and t_per_n are per n).
// schlick_rv switches to a 64-term series for |1 − n| ≤ ½.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "specula/io/values.h"
#include "specula/lobes/lobes.h"
#include "specula/normalize/closed_form.h"
#include "specula/normalize/quadrature.h"

namespace {

using namespace specula;

using ClosedForm = double (*)(double);

void set_per_n(benchmark::State& state, std::size_t values_per_iteration) {
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(values_per_iteration));
  state.counters["t_per_n"] = benchmark::Counter(
      static_cast<double>(values_per_iteration),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// One closed form at one n, called back to back (independent calls: throughput, not latency).
template <ClosedForm F>
void bm_closed_form(benchmark::State& state, double n) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(n);  // n is opaque: no hoisting or constant folding
    double k = F(n);
    benchmark::DoNotOptimize(k);
  }
  set_per_n(state, 1);
}

/// One closed form over a list of n per iteration.
template <ClosedForm F>
void bm_closed_form_list(benchmark::State& state, std::vector<double> ns) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(ns.data());
    for (double n : ns) {
      double k = F(n);
      benchmark::DoNotOptimize(k);
    }
    benchmark::ClobberMemory();
  }
  set_per_n(state, ns.size());
}

/// normalize::quadrature(lobe, form): adaptive Gauss-Kronrod over u = −ln c.
void bm_quadrature(benchmark::State& state, lobes::Lobe lobe, Form form) {
  for (auto _ : state) {
    benchmark::DoNotOptimize(lobe);
    double k = normalize::quadrature(lobe, form);
    benchmark::DoNotOptimize(k);
  }
  set_per_n(state, 1);
}

struct NValue {
  const char* label;
  double n;
};

template <ClosedForm F>
void register_closed_form(const std::string& name, std::initializer_list<NValue> values,
                          bool with_huge) {
  const std::string prefix = "normalize/" + name + "/closed_form/";
  for (const NValue& v : values)
    benchmark::RegisterBenchmark((prefix + "n:" + v.label).c_str(), bm_closed_form<F>, v.n);
  benchmark::RegisterBenchmark((prefix + "paper50").c_str(), bm_closed_form_list<F>,
                               io::paper50());
  if (with_huge)
    benchmark::RegisterBenchmark((prefix + "1e6..1e9").c_str(), bm_closed_form_list<F>,
                                 std::vector<double>{1e6, 1e7, 1e8, 1e9});
}

template <template <class> class L>
void register_quadrature(const char* family) {
  for (const Form form : {Form::rv, Form::nh}) {
    for (const NValue& v : {NValue{"20", 20.0}, NValue{"1e6", 1e6}}) {
      const std::string name = std::string("normalize/quadrature/") + family + "/" +
                               to_string(form) + "/n:" + v.label;
      benchmark::RegisterBenchmark(name.c_str(), bm_quadrature, lobes::Lobe{L<double>{v.n}}, form)
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

[[maybe_unused]] const bool registered = [] {
  // a = 2 ln 2/n: 1386 (asymptotic, both), 139 (asymptotic, both), 13.9 (expint / asymptotic
  // for 4a), 1.39 (expint), 0.99 (series, near its worst), then ever faster series.
  register_closed_form<lobes::log_rv>(
      "log_rv",
      {{"0.001", 1e-3}, {"0.01", 1e-2}, {"0.1", 0.1}, {"1", 1.0}, {"1.4", 1.4}, {"2", 2.0},
       {"20", 20.0}, {"1000", 1000.0}, {"1e6", 1e6}, {"1e9", 1e9}},
      true);
  register_closed_form<lobes::schlick_rv>(
      "schlick_rv",
      {{"0.001", 1e-3}, {"0.75", 0.75}, {"1", 1.0}, {"20", 20.0}, {"1000", 1000.0}, {"1e9", 1e9}},
      true);
  register_closed_form<lobes::blinn_phong_nh>("blinn_phong_nh", {{"20", 20.0}}, false);

  register_quadrature<lobes::Log>("log");
  register_quadrature<lobes::Power>("power");
  register_quadrature<lobes::Gauss>("gauss");
  return true;
}();

}  // namespace
