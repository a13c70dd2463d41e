#pragma once
// GLSL functions timed on the GPU (or on Mesa's llvmpipe where there is none): each function
// `float specula_term(float v0, …, float p)` evaluated many times per pixel by a fragment shader
// over a full-screen draw, the draws timed by the wall clock around glFinish, the same shader
// around the function that returns its first variable subtracted (docs/designer.md, "Cost as a
// GPU sees it").
#include <string>
#include <vector>

#include "specula/gl/context.h"

namespace specula::gl {

/// A function to time: GLSL defining `float specula_term(...)` of `variables` per-pixel variables
/// (each in (0, 1]) and then the parameter (if `has_param`), set to `param`.
struct GlslFunction {
  std::string glsl;
  int variables = 1;
  bool has_param = false;
  double param = 0;
};

/// Picoseconds per evaluation of each function (beyond the baseline's), the fastest of `trials`
/// timings, each of the functions in turn in every trial. A function that does not compile is
/// NaN. Throws GlError when the context fails.
std::vector<double> time_functions(const Context& context, const std::vector<GlslFunction>& functions, int trials = 5);

}  // namespace specula::gl
