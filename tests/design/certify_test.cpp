// The certified bound (src/design/certify.h) against dense evaluations here: never below the
// largest error a dense grid finds, and within the bound's tolerance above it.
#include <cmath>
#include <gtest/gtest.h>

#include "design/certify.h"
#include "function_settings.h"
#include "specula/brdf/fresnel.h"
#include "specula/design/design.h"

namespace specula::design {
namespace {

const auto never = [] { return false; };

TEST(Certify, ABoundIsNeverBelowTheDenseMaximumAndCloseAboveIt) {
  const Settings s = function_settings("schlick-weight");
  double dense = 0;
  for (int i = 0; i <= 200000; ++i) {
    const double c = kCertifiedFloor + (1 - kCertifiedFloor) * i / 200000.0;
    dense = std::max(dense, std::abs(std::exp(-5 * c) - std::pow(1 - c, 5)));
  }
  const Certified c = certify(s, "exp(-5*c)", 0, never);
  EXPECT_GE(c.bound, dense);
  EXPECT_LE(c.bound, dense * (1 + kCertifyTolerance) + 1e-9);
  EXPECT_GE(c.found, dense * (1 - kCertifyTolerance));  // a box's centre comes as close as the bound
  EXPECT_LT(c.boxes, kMaxCertifyBoxes);
  // The control: the term itself is bounded by 0, which the dense maximum above is not.
  EXPECT_EQ(certify(s, "(1 - c)^5", 0, never).bound, 0);
  EXPECT_GT(dense, 0.05);
}

// Schlick's Fresnel over (c, η) ∈ [10⁻⁶, 1] × [1.2, 2.5]: a box of two dimensions, one of them the
// range parameter. (Under 0.1 s under the sanitizers.)
TEST(Certify, SchlicksFresnelIsBoundedOverTheWholeRange) {
  const Settings s = function_settings("fresnel-dielectric");
  double dense = 0;
  for (int j = 0; j <= 130; ++j) {
    const double eta = 1.2 + 1.3 * j / 130.0, f0 = std::pow((eta - 1) / (eta + 1), 2);
    for (int i = 0; i <= 4000; ++i) {
      const double c = std::max(kCertifiedFloor, std::pow(i / 4000.0, 2));
      dense = std::max(dense, std::abs(f0 + (1 - f0) * std::pow(1 - c, 5) - fresnel::dielectric(c, eta)));
    }
  }
  EXPECT_NEAR(dense, 0.113, 1e-3);
  const Certified c = certify(s, "fresnel_schlick(c, ((eta - 1)/(eta + 1))^2)", 0, never);
  EXPECT_GE(c.bound, dense);
  EXPECT_LE(c.bound, dense * (1 + kCertifyTolerance) + 1e-9);
}

}  // namespace
}  // namespace specula::design
