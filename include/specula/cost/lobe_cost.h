#pragma once
// The lobe benchmark behind `make bench`, `specula bench` and the report's cost section: for every
// lobe, ns per evaluation through the scalar lobe (libm) and the SIMD exact and fast tiers, in
// cache and streaming from memory, on one core and on all of them (oneTBB); the accuracy of each
// path against the scalar double lobe and each lobe's distance from cⁿ; the machine's two limits
// (its peak vector rate times the kernel's operations, and its streaming bandwidth) and each
// lobe's distance from the nearer one. docs/simd.md explains how to read it. (Module `cost`, the
// measurement as a library function; bench/ at the top holds the Google Benchmark programs.)
#include <cstddef>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "specula/lobes/lobes.h"
#include "specula/simd/lobes.h"

namespace specula::cost {

/// Which implementation evaluates the lobe.
enum class Path { scalar, exact, fast };  ///< scalar: the lobe struct per value (std::pow, log2…)
inline constexpr std::size_t kPathCount = static_cast<std::size_t>(Path::fast) + 1;  // fast: the last

/// "scalar", "exact" or "fast".
const char* to_string(Path path) noexcept;

struct Settings {
  double n = 20;                          ///< every lobe's exponent
  std::size_t cache_bytes = 4096;         ///< in-cache input array (the output is as large)
  std::size_t stream_bytes = 256u << 20;  ///< streamed input array (the output is as large)
  double trial_seconds = 0.02;            ///< length of one in-cache trial
  int trials = 5;                         ///< in-cache: fastest of; streaming: fastest of ⌈trials/2⌉ passes
  bool doubles = true;                    ///< double lanes too (float always)
  bool streaming = true;
  bool threaded = true;                   ///< all cores as well as one (oneTBB)
  std::size_t accuracy_points = 1 << 15;  ///< cosines per region of the accuracy probe
  /// User lobe models (registered ids, catalogue/model_file.h) measured beside the built-ins, at n
  /// where they have a parameter n: scalar = the Formula per value (expr::Program, libm), exact
  /// and fast = the vectorized formula path (simd/formula.h).
  std::vector<std::string> user_lobes;
  /// The same settings with user_lobes = every registered user lobe model (models()).
  Settings with_registered_user_lobes() const;

  static Settings full() { return {}; }
  /// A few seconds: smaller streamed arrays, shorter and fewer trials.
  static Settings quick();
  /// What the report shows: in cache, one core, float and double.
  static Settings report(bool quick);
};

/// One lobe through one path in one precision. Times are ns per evaluation per core (wall time ×
/// cores / evaluations); NaN where not measured.
struct Measurement {
  simd::Family family;  ///< Family::formula for a user lobe
  std::string lobe;     ///< the family's name (families/<family>.h), or the user model's id
  Path path;
  bool single = true;  ///< float lanes (else double)
  double cache_ns = NAN, cache_threads_ns = NAN, stream_ns = NAN, stream_threads_ns = NAN;
  double max_rel_error = 0;  ///< against the scalar double lobe, where F ≥ 1e-3 (F's peak is 1)
  double max_abs_error = 0;  ///< against the scalar double lobe, everywhere
  double ops_per_value = NAN;  ///< SIMD paths: the kernel's vector operations per value

  double evals_per_s_per_core() const noexcept { return 1e9 / cache_ns; }
};

struct Machine {
  std::string target;  ///< Highway's dispatched target, e.g. AVX3
  std::size_t lanes_f32 = 0, lanes_f64 = 0;
  int threads = 1;
  double fma_per_s = NAN;          ///< vector FMAs per second, one core (measured)
  double copy_bytes_per_s = NAN;   ///< streaming copy, read + written bytes, one core
  double copy_bytes_per_s_all = NAN;  ///< the same on every core
  double sum_bytes_per_s = NAN;    ///< streaming read-only sum, one core
};

struct Result {
  Settings settings;
  Machine machine;
  std::vector<Measurement> rows;             ///< lobes × paths × precisions
  std::vector<std::string> lobes;            ///< the built-in families (simd::Family order), then the user lobes
  std::vector<double> error_vs_power;        ///< per lobe (lobes' order): max |F − cⁿ| at n

  const Measurement& at(simd::Family family, Path path, bool single) const;
  const Measurement& at(std::string_view lobe, Path path, bool single) const;
  /// ns per value at the compute limit: ops per value ÷ the peak vector rate (SIMD paths).
  double compute_limit_ns(const Measurement& m) const noexcept;
  /// ns per value at the memory limit: bytes per value (read c, write F) ÷ copy bandwidth.
  double memory_limit_ns(const Measurement& m, bool all_cores) const noexcept;
};

/// Runs the benchmark; `progress` is told each phase as it starts.
Result run(const Settings& settings, const std::function<void(std::string_view)>& progress = {});

/// Plain-text tables: per precision, every lobe and path with its times, ratios, errors and
/// limits; the baselines (cⁿ through libm and through the SIMD path, Schlick's rational form).
std::string to_table(const Result& result);

/// JSON: the machine, the settings, and per lobe and path: evals_per_s_per_core (in cache,
/// float), max_rel_error against the scalar double lobe, every time measured, the limits.
std::string to_json(const Result& result);

/// A float kernel: out[i] = F(c[i]) for the whole span.
using FloatKernel = std::function<void(std::span<const float> c, std::span<float> out)>;

/// ns per value of each kernel as the benchmark times a lobe in cache on one core (`cache_bytes`
/// of its peaked cosines, the fastest of `trials` trials of `trial_seconds`, the kernels in turn):
/// the harness in which the lobe designer times its lobes beside the built-in ones.
std::vector<double> time_in_cache(std::span<const FloatKernel> kernels, const Settings& settings);

/// The benchmark's kernel for `lobe` (copied) on `path`, in float lanes.
FloatKernel lobe_kernel(const lobes::Lobe& lobe, Path path);
}  // namespace specula::cost
