#include "specula/gl/timing.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <memory>
#include <optional>

#include "gl_api.h"
#include "target.h"

namespace specula::gl {
namespace {

constexpr int kSide = 256;           // pixels a side of each draw
constexpr int kPerPixel = 64;        // evaluations per pixel
constexpr double kMinSeconds = 0.02; // a timing's least duration: draws are repeated until then

constexpr const char* kVertex =
    "#version 330 core\n"
    "void main() {\n"
    "  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
    "  gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);\n"
    "}\n";

// Each pixel evaluates the function kPerPixel times at inputs spread over (0, 1] (a different
// golden-ratio step per variable), summing the results so that none is optimized away.
std::string fragment_shader(const GlslFunction& f) {
  std::string arguments;
  for (int v = 0; v < f.variables; ++v) arguments += fmt::format("{}x[{}]", v ? ", " : "", v);
  if (f.has_param) arguments += ", u_param";
  return fmt::format(
      "#version 330 core\n"
      "uniform float u_param;\n"
      "out vec4 o_colour;\n"
      "{}\n"
      "void main() {{\n"
      "  float x[3] = float[3](fract(gl_FragCoord.x * 0.0061803), fract(gl_FragCoord.y * 0.0041421), 0.5);\n"
      "  float sum = 0.0;\n"
      "  for (int i = 0; i < {}; ++i) {{\n"
      "    for (int v = 0; v < 3; ++v) x[v] = max(fract(x[v] + 0.61803398875 + 0.1 * float(v)), 1e-3);\n"
      "    sum += specula_term({});\n"
      "  }}\n"
      "  o_colour = vec4(sum);\n"
      "}}\n",
      f.glsl, kPerPixel, arguments);
}

// Seconds per draw of `program` over kSide², the fastest of the draws in a timing of at least kMinSeconds.
double seconds_per_draw(const Program& program, double param) {
  glUseProgram(program.id());
  glUniform1f(glGetUniformLocation(program.id(), "u_param"), static_cast<float>(param));
  glViewport(0, 0, kSide, kSide);
  using Clock = std::chrono::steady_clock;
  int draws = 1;
  for (;;) {
    glFinish();
    const auto start = Clock::now();
    for (int i = 0; i < draws; ++i) glDrawArrays(GL_TRIANGLES, 0, 3);
    glFinish();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (seconds >= kMinSeconds || draws >= (1 << 16)) return seconds / draws;
    draws *= 2;
  }
}

}  // namespace

std::vector<double> time_functions(const Context& context, const std::vector<GlslFunction>& functions, int trials) {
  context.make_current();
  (void)context.target(kSide, kSide);  // current and bound
  // One baseline program per signature (variables, parameter), timed beside each function.
  std::map<std::pair<int, bool>, std::unique_ptr<Program>> baseline_of;
  std::vector<std::unique_ptr<Program>> programs;
  std::vector<const Program*> baselines;
  for (const GlslFunction& f : functions) {
    auto& shared = baseline_of[{f.variables, f.has_param}];
    if (!shared) {
      GlslFunction first = f;
      std::string parameters;
      for (int v = 0; v < f.variables; ++v) parameters += fmt::format("{}float v{}", v ? ", " : "", v);
      if (f.has_param) parameters += ", float p";
      first.glsl = fmt::format("float specula_term({}) {{ return v0; }}\n", parameters);
      shared = std::make_unique<Program>(context, kVertex, fragment_shader(first));
    }
    try {
      programs.push_back(std::make_unique<Program>(context, kVertex, fragment_shader(f)));
    } catch (const GlError&) {
      programs.push_back(nullptr);
    }
    baselines.push_back(shared.get());
  }
  std::vector<double> fastest(functions.size(), INFINITY), baseline(functions.size(), INFINITY);
  for (int trial = 0; trial < trials; ++trial)
    for (std::size_t i = 0; i < functions.size(); ++i) {
      if (!programs[i]) continue;
      fastest[i] = std::min(fastest[i], seconds_per_draw(*programs[i], functions[i].param));
      baseline[i] = std::min(baseline[i], seconds_per_draw(*baselines[i], functions[i].param));
    }
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    throw GlError(fmt::format("OpenGL error 0x{:04x} while timing functions", error));
  constexpr double kEvaluations = static_cast<double>(kSide) * kSide * kPerPixel;
  std::vector<double> ps(functions.size(), NAN);
  for (std::size_t i = 0; i < functions.size(); ++i)
    if (programs[i]) ps[i] = std::max(0.0, (fastest[i] - baseline[i]) / kEvaluations * 1e12);
  return ps;
}

}  // namespace specula::gl
