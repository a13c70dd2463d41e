// Energy conservation, reciprocity and non-negativity verdicts (issue: what `check` must get
// right), and the strict normalization.
#include <gtest/gtest.h>

#include <cmath>

#include "specula/analysis/albedo.h"
#include "specula/analysis/check.h"
#include "specula/normalize/normalize.h"

namespace specula::analysis {
namespace {

CheckOptions fast(double step = 10, std::vector<double> grazing = {89.5, 89.9}) {
  CheckOptions o;
  o.grid_step_deg = step;
  o.grazing_deg = std::move(grazing);
  o.reciprocity_pairs = 2000;
  return o;
}

TEST(Check, NormalizedPhongAndLogConserveEnergyInRvForm) {
  for (const double n : {1.0, 20.0, 1000.0})
    for (const char* id : {"phong-normalized", "log-normalized"}) {
      const CheckResult r = check(make_model(id, {{"n", n}}), fast());
      EXPECT_TRUE(r.all_hold()) << id << " n=" << n;
      EXPECT_NEAR(r.albedo_normal, 1, 1e-12);
      EXPECT_NEAR(r.max_albedo.value, 1, 1e-9);
      EXPECT_EQ(r.max_albedo.theta_deg, 0);
    }
}

TEST(Check, CookTorrance1982ReflectsAboutFourTimesWhatItReceives) {
  const CheckResult r = check(make_model("cook-torrance-1982"), fast(30, {}));
  EXPECT_FALSE(r.conserves_energy);
  EXPECT_TRUE(r.reciprocal);
  EXPECT_TRUE(r.non_negative);
  EXPECT_GT(r.max_albedo.value, 3.9);
  // The modern form is exactly a quarter of it: D lacks 1/π, 4 replaces π in the denominator.
  EXPECT_NEAR(albedo(make_model("cook-torrance-1982"), 0.5).value,
              4 * albedo(make_model("cook-torrance"), 0.5).value, 1e-8);
}

TEST(Check, Ward1992HoldsWhereDuersVariantBlowsUpAtGrazing) {
  const CheckResult ward = check(make_model("ward", {{"alpha", 0.2}}), fast());
  const CheckResult duer = check(make_model("ward-duer", {{"alpha", 0.2}}), fast());
  const CheckResult gmd = check(make_model("ward-gmd", {{"alpha", 0.2}}), fast());
  EXPECT_TRUE(ward.conserves_energy);
  EXPECT_FALSE(duer.conserves_energy);
  EXPECT_GT(duer.max_albedo.theta_deg, 85);  // the failure is at grazing incidence
  EXPECT_LT(albedo(make_model("ward-duer", {{"alpha", 0.2}}), 0).value, 1);
  EXPECT_TRUE(gmd.conserves_energy);
  EXPECT_TRUE(ward.reciprocal && duer.reciprocal && gmd.reciprocal);
}

TEST(Check, LogNormalizedInNhFormBreaksAndTheNhCoefficientFixesIt) {
  const Model wrong = make_model("log-normalized", {{"n", 20}}, Form::nh);
  const CheckResult broken = check(wrong, fast());
  EXPECT_FALSE(broken.conserves_energy);
  EXPECT_GT(broken.albedo_normal, 3);
  const double k_nh = normalize::coefficient(wrong.lobe(), Form::nh);
  const CheckResult fixed = check(wrong.with_coef(k_nh), fast());
  EXPECT_TRUE(fixed.all_hold());
  EXPECT_NEAR(fixed.albedo_normal, 1, 1e-10);
}

TEST(Check, ReportsTheFailingPropertyOnly) {
  const CheckResult r = check(make_model("phong", {{"n", 1}}), fast());  // k = 1: ρ(0) = 2π/3
  EXPECT_FALSE(r.conserves_energy);
  EXPECT_NEAR(r.albedo_normal, 2 * std::numbers::pi / 3, 1e-12);
  EXPECT_TRUE(r.reciprocal);
  EXPECT_TRUE(r.non_negative);
}

TEST(Strict, EqualsThePapersConditionWhenTheMaximumIsAtNormalIncidence) {
  const Model m = make_model("log-normalized", {{"n", 20}});
  EXPECT_NEAR(strict_coefficient(m, 10), normalize::log_rv(20), 1e-10 * normalize::log_rv(20));
}

TEST(Strict, MakesTheMaximumAlbedoOne) {
  const Model gauss = make_model("gauss", {{"n", 10}});
  const double k = strict_coefficient(gauss, 5);
  EXPECT_NEAR(max_albedo(gauss.with_coef(k), 5).value, 1, 1e-9);
}

}  // namespace
}  // namespace specula::analysis
