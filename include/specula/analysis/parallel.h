#pragma once
// Sweeps over parameter values run in parallel (oneTBB); each result lands at its input's index,
// so the output is bit-identical whatever the thread count. Each element runs under the caller's
// work limit and checks it first (specula/interrupt): a stopped sweep throws Interrupted.
#include <span>
#include <tbb/parallel_for.h>
#include <type_traits>
#include <vector>

#include "specula/interrupt/interrupt.h"

namespace specula::analysis {

template <class T, class F>
auto parallel_map(std::span<const T> inputs, const F& f) {
  std::vector<std::invoke_result_t<const F&, const T&>> out(inputs.size());
  const auto one = [&](std::size_t i) {
    check_interrupt();
    out[i] = f(inputs[i]);
  };
  tbb::parallel_for(std::size_t{0}, inputs.size(), carry_limit(one));
  return out;
}

}  // namespace specula::analysis
