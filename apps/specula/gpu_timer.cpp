#include "gpu_timer.h"

#include "specula/gl/context.h"
#include "specula/gl/timing.h"

namespace specula::cli {

design::GpuTiming time_on_gpu(const std::vector<design::GpuFunction>& functions) {
  try {
    const gl::Context context;
    std::vector<gl::GlslFunction> glsl;
    for (const auto& f : functions) glsl.push_back({f.glsl, f.variables, f.has_param, f.param});
    return {gl::time_functions(context, glsl), gl::to_string(context.info())};
  } catch (const gl::GlError& e) {
    return {{}, e.what()};
  }
}

}  // namespace specula::cli
