#include "build_info.h"

#include <fmt/format.h>

#include "specula/simd/targets.h"

namespace specula::cli {

std::string version_line() {
  return fmt::format("specula {} (commit {}), SIMD: {}", build_version(), build_commit(),
                     simd::current_target().name);
}

}  // namespace specula::cli
