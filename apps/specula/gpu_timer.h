#pragma once
// The designer's GPU cost axis as the CLI makes it: functions timed in an offscreen GL context
// (the GPU, or Mesa's llvmpipe without one), for `specula design` and `specula report`.
#include "specula/design/design.h"

namespace specula::cli {

design::GpuTiming time_on_gpu(const std::vector<design::GpuFunction>& functions);

}  // namespace specula::cli
