// Every compensation as a model (models/compensated.h): `M+kulla-conty`, `M+turquin-f0`,
// `M+turquin-f`, `M+turquin-favg` and `M+cycles` are models whose albedo, computed by specula's
// cubature of M and the model's own table, is the verdict's closed form (queries/compensation.h)
// on inputs computed apart: the cubature albedos of M with F = 1 and with its F0, and Schlick's F.
// A scaled one is not reciprocal and its albedo is the viewer's; the Monte-Carlo estimator, which
// evaluates the whole f through the SIMD batch, agrees with it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "specula/analysis/albedo.h"
#include "specula/analysis/check.h"
#include "specula/analysis/monte_carlo.h"
#include "specula/brdf/fresnel.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/queries/compensation.h"

namespace specula::queries {
namespace {

struct Named {
  std::string suffix;
  Compensation formula;
};

const Named kSchemes[] = {{"+kulla-conty", Compensation::kulla_conty},
                          {"+turquin-f0", Compensation::turquin_f0},
                          {"+turquin-f", Compensation::turquin_fresnel},
                          {"+turquin-favg", Compensation::turquin_average},
                          {"+cycles", Compensation::cycles}};

/// The verdict's inputs for GGX at (α, F0, θ) with the model's table: E(μ) as the table holds it
/// (EachSuffixsTableIsTheCubaturesWithinItsError ties it to the cubature), the rest each from a
/// computation of its own.
CompensationInputs inputs(double alpha, double f0, double theta, const EnergyTable& table) {
  const double mu = std::cos(theta);
  return {table.at(mu), table.e_avg,
          analysis::albedo(make_model("ggx", {{"alpha", alpha}, {"f0", f0}}), theta).value, fresnel::schlick(mu, f0),
          f0, fresnel::schlick_average(f0)};
}

/// How far the model's albedo may be from the formula's: the cubature's error, and f_ms's albedo
/// integrated over the interpolant (ms_scale, 1 within the table's error) for the added lobe.
double tolerance(const Compensated& c) { return 1e-9 + std::abs(c.table->ms_scale - 1); }

TEST(CompensationModels, EachSuffixsAlbedoIsTheVerdictsFormula) {
  for (const double alpha : {0.3, 1.0})
    for (const double f0 : {0.04, 0.5})
      for (const Named& s : kSchemes) {
        const Model model = make_model("ggx" + s.suffix, {{"alpha", alpha}, {"f0", f0}});
        const Compensated& parts = *model.compensated();
        for (const double theta : {0.0, 1.0, 1.4}) {
          const CompensationInputs in = inputs(alpha, f0, theta, *parts.table);
          const double albedo = analysis::albedo(model, theta).value;
          EXPECT_NEAR(albedo, compensated_albedo(s.formula, in), tolerance(parts))
              << model.id() << " alpha " << alpha << " f0 " << f0 << " theta " << theta;
        }
      }
}

// The table every suffix reads is M's with F = 1, the cubature's to its stated interpolation error.
TEST(CompensationModels, EachSuffixsTableIsTheCubaturesWithinItsError) {
  for (const Named& s : kSchemes) {
    const Model model = make_model("ggx" + s.suffix, {{"alpha", 0.5}, {"f0", 0.2}});
    const EnergyTable& table = *model.compensated()->table;
    EXPECT_FALSE(table.from_walk) << s.suffix;
    for (const double theta : {0.0, 1.0, 1.4}) {
      const double e = analysis::albedo(make_model("ggx", {{"alpha", 0.5}, {"f0", 1}}), theta).value;
      EXPECT_NEAR(table.at(std::cos(theta)), e, 1.5 * table.interpolation_error) << s.suffix << " theta " << theta;
    }
  }
}

// The control: each formula checked as above against another suffix's model misses, except where
// two formulas agree (F0 against F(μ) at normal incidence).
TEST(CompensationModels, AnotherSuffixsAlbedoMissesTheFormula) {
  const double alpha = 1, f0 = 0.2, theta = 1.0;
  for (const Named& s : kSchemes)
    for (const Named& other : kSchemes) {
      if (s.suffix == other.suffix) continue;
      const Model model = make_model("ggx" + other.suffix, {{"alpha", alpha}, {"f0", f0}});
      const CompensationInputs in = inputs(alpha, f0, theta, *model.compensated()->table);
      EXPECT_GT(std::abs(analysis::albedo(model, theta).value - compensated_albedo(s.formula, in)),
                10 * tolerance(*model.compensated()))
          << s.suffix << " against " << other.suffix;
    }
}

TEST(CompensationModels, AModelWithoutAFresnelGetsTheWhiteCompensation) {
  // F ≡ 1: Turquin's scale is 1/E and Kulla & Conty's lobe gives back 1 − E; the albedo is 1.
  for (const Named& s : kSchemes) {
    const Model model = make_model("log-normalized" + s.suffix, {{"n", 5}});
    for (const double theta : {0.0, 0.8, 1.3})
      EXPECT_NEAR(analysis::albedo(model, theta).value, 1, 2 * model.compensated()->table->albedo_error + 1e-6)
          << model.id() << " theta " << theta;
  }
  EXPECT_LT(analysis::albedo(make_model("log-normalized", {{"n", 5}}), 1.3).value, 0.99);  // the control
}

// The scaled compensations are not reciprocal, the added one is; their albedo is the viewer's,
// which the Monte-Carlo estimator (V held fixed, L sampled, the whole f evaluated) confirms.
TEST(CompensationModels, ScaledOnesAreTheViewersAndNotReciprocal) {
  analysis::CheckOptions options;
  options.grid_step_deg = 30;
  options.reciprocity_pairs = 2000;
  for (const Named& s : kSchemes) {
    const Model model = make_model("ggx" + s.suffix, {{"alpha", 0.6}, {"f0", 0.2}});
    EXPECT_EQ(model.fixes_viewer(), s.suffix != "+kulla-conty") << s.suffix;
    EXPECT_EQ(analysis::check(model, options).reciprocal, !model.fixes_viewer()) << s.suffix;
    const double theta = 1.2;
    const auto mc = analysis::albedo_monte_carlo(model, theta, 1 << 17, 7);
    EXPECT_NEAR(mc.mean, analysis::albedo(model, theta).value, 4 * mc.standard_error + 1e-4) << s.suffix;
  }
}

TEST(CompensationModels, NamesResolveAndRefuseWhatTheyShould) {
  EXPECT_EQ(compensated_base_id("ggx+turquin-favg"), "ggx");
  EXPECT_EQ(compensation_scheme_of("ggx+turquin-f"), CompensationScheme::turquin_f);
  EXPECT_EQ(compensation_scheme_of("ggx+turquin-f0"), CompensationScheme::turquin_f0);
  EXPECT_EQ(compensation_scheme_of("ggx"), CompensationScheme::shipped);
  EXPECT_THROW(make_model("ggx+cycles+ms"), InvalidField);
  EXPECT_THROW(make_model("ggx+turquin"), InvalidField);
  EXPECT_THROW(make_model("nosuch+cycles"), InvalidField);
  EXPECT_EQ(make_model("ggx+cycles", {{"alpha", 0.2}}).param("alpha"), 0.2);
}

}  // namespace
}  // namespace specula::queries
