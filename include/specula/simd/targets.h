#pragma once
// Which instruction set the SIMD batch functions run on (Highway's dynamic dispatch), a scope
// that restricts dispatch to one target (so that tests hold every compiled target to the same
// error bounds), and what the machine can do: its peak vector FMA rate and streaming bandwidth,
// the two limits of the benchmark (docs/simd.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace specula::simd {

struct TargetInfo {
  std::string name;         ///< Highway's name, e.g. "AVX3", "AVX2", "SSE4", "NEON", "EMU128"
  std::size_t lanes_f32;    ///< float lanes of one vector
  std::size_t lanes_f64;
};

/// The target dispatch picks now (the best the CPU supports, unless a ScopedTarget is active).
TargetInfo current_target();

/// Every target compiled into specula that this CPU can run, best first, by Highway's bit.
std::vector<std::int64_t> runnable_targets();
std::string target_name(std::int64_t target);

/// While alive, dispatch uses only `target` (one of runnable_targets()); restores the normal
/// choice when destroyed. For tests and benchmarks; not thread-safe against concurrent batches.
/// Vector FMAs per second on the calling thread's core, measured on the dispatched target: 12
/// independent accumulators (enough to cover the FMA latency × issue width of current cores)
/// for about `seconds`.
double measure_fma_per_second(double seconds);

/// Streaming copy out[i] = in[i] and sum of in[], with the dispatched target's widest vectors
/// and ordinary (not non-temporal) stores, as the batch lobes read and write. Timing is the
/// caller's.
void stream_copy(const float* in, float* out, std::size_t count);
float stream_sum(const float* in, std::size_t count);

class ScopedTarget {
 public:
  explicit ScopedTarget(std::int64_t target);
  ~ScopedTarget();
  ScopedTarget(const ScopedTarget&) = delete;
  ScopedTarget& operator=(const ScopedTarget&) = delete;
};

}  // namespace specula::simd
