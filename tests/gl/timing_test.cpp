// GLSL functions timed in the offscreen context (include/specula/gl/timing.h): a function of more
// work costs more than one of less, the baseline F = its first variable costs 0 beyond itself,
// and a function that does not compile is NaN, not an error.
#include "specula/gl/timing.h"

#include <cmath>
#include <gtest/gtest.h>
#include <string>

#include "gl_support.h"

namespace specula::gl {
namespace {

using specula::testing::shared_context;

TEST(GpuTiming, MoreWorkCostsMoreAndABrokenFunctionIsNaN) {
  std::string heavy = "x";
  for (int i = 0; i < 12; ++i) heavy = "exp(sin(" + heavy + ") * 0.5)";
  const std::vector<GlslFunction> functions{
      {"float specula_term(float x, float p) { return x * p + 0.25; }", 1, true, 0.5},
      {"float specula_term(float x, float p) { return " + heavy + " * p; }", 1, true, 0.5},
      {"float specula_term(float x) { return x; }", 1, false, 0},  // the baseline itself
      {"float specula_term(float x) { return nosuch(x); }", 1, false, 0},
      {"float specula_term(float a, float b) { return a * b; }", 2, false, 0}};
  const std::vector<double> ps = time_functions(shared_context(), functions, 3);
  ASSERT_EQ(ps.size(), functions.size());
  EXPECT_GT(ps[1], 4 * ps[0]) << ps[0] << " " << ps[1];  // 24 transcendental calls against one FMA
  EXPECT_GT(ps[1], 1);
  EXPECT_LT(ps[2], ps[1] / 10);  // the baseline, beyond itself: about 0
  EXPECT_TRUE(std::isnan(ps[3]));
  EXPECT_TRUE(std::isfinite(ps[4]));
}

}  // namespace
}  // namespace specula::gl
