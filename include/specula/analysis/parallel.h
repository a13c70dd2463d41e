#pragma once
// Sweeps over parameter values run in parallel (oneTBB); each result lands at its input's index,
// so the output is bit-identical whatever the thread count.
#include <span>
#include <tbb/parallel_for.h>
#include <type_traits>
#include <vector>

namespace specula::analysis {

template <class T, class F>
auto parallel_map(std::span<const T> inputs, const F& f) {
  std::vector<std::invoke_result_t<const F&, const T&>> out(inputs.size());
  tbb::parallel_for(std::size_t{0}, inputs.size(), [&](std::size_t i) { out[i] = f(inputs[i]); });
  return out;
}

}  // namespace specula::analysis
