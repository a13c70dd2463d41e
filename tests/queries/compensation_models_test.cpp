// Every compensation as a model (models/compensated.h): `M+kulla-conty`, `M+turquin-f0`,
// `M+turquin-f`, `M+turquin-favg` and `M+cycles` are models whose albedo, computed by specula's
// cubature of M and the model's own table, is the verdict's closed form (queries/compensation.h)
// on inputs computed apart: the cubature albedos of M with F = 1 and with its F0, and Schlick's F.
// A scaled one is not reciprocal and its albedo is the viewer's; the Monte-Carlo estimator, which
// evaluates the whole f through the SIMD batch, agrees with it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "specula/analysis/albedo.h"
#include "specula/analysis/check.h"
#include "specula/analysis/fresnel.h"
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

// Every Fresnel kind of a microfacet model (families/fresnel.h) is what the suffixes read: the
// same formula, with F(μ), F0 and F_avg of the model's own channel, and the table of its family's
// F = 1 model (GGX's or Beckmann's at F0 = 1) as the white table.
struct FresnelCase {
  std::string id;
  ParamValues params;
  fresnel::Channel channel;
  std::string white;  ///< the family's model whose F0 = 1 is F ≡ 1
};

std::vector<FresnelCase> fresnel_cases() {
  using fresnel::Kind;
  return {{"ggx-f82", {{"alpha", 0.6}, {"f0", 0.9}, {"tint", 0.7}}, {.kind = Kind::f82_tint, .f0 = 0.9, .tint = 0.7}, "ggx"},
          {"ggx-dielectric", {{"alpha", 0.6}, {"eta", 1.5}}, {.kind = Kind::dielectric, .eta = 1.5}, "ggx"},
          {"ggx-conductor", {{"alpha", 0.6}, {"eta", 0.2}, {"kappa", 3.1}}, {.kind = Kind::conductor, .eta = 0.2, .kappa = 3.1}, "ggx"},
          {"ggx-schlick", {{"alpha", 0.6}, {"f0", 0.3}, {"f90", 0.8}, {"exponent", 3}},
           {.kind = Kind::schlick, .f0 = 0.3, .f90 = 0.8, .exponent = 3}, "ggx"},
          {"beckmann-conductor", {{"alpha", 0.6}, {"eta", 1.1}, {"kappa", 2.5}},
           {.kind = Kind::conductor, .eta = 1.1, .kappa = 2.5}, "beckmann"},
          {"beckmann", {{"alpha", 0.6}, {"f0", 0.04}}, {.kind = Kind::schlick, .f0 = 0.04}, "beckmann"}};
}

TEST(CompensationModels, EveryFresnelKindIsTheModelsOwn) {
  for (const FresnelCase& c : fresnel_cases()) {
    const double f_avg = analysis::fresnel_average(c.channel).value;
    const Model white = make_model(c.white, {{"alpha", c.params.at("alpha")}, {"f0", 1}});
    for (const Named& s : kSchemes) {
      if (c.id == "beckmann" && s.suffix == "+turquin-f0") continue;  // as ggx's: covered above
      const Model model = make_model(c.id + s.suffix, c.params);
      const Compensated& parts = *model.compensated();
      for (const double theta : {0.0, 1.0, 1.4}) {
        const double mu = std::cos(theta);
        EXPECT_NEAR(parts.table->at(mu), analysis::albedo(white, theta).value, 1.5 * parts.table->interpolation_error)
            << model.id() << " theta " << theta;
        const CompensationInputs in{parts.table->at(mu), parts.table->e_avg,
                                    analysis::albedo(make_model(c.id, c.params), theta).value, c.channel(mu),
                                    c.channel(1.0), f_avg};
        EXPECT_NEAR(analysis::albedo(model, theta).value, compensated_albedo(s.formula, in), tolerance(parts))
            << model.id() << " theta " << theta;
      }
    }
  }
}

// The control: the conductor's model read with the dielectric's channel of the same η misses.
TEST(CompensationModels, AnotherChannelMissesTheFresnelKindsFormula) {
  const ParamValues params{{"alpha", 0.6}, {"eta", 0.2}, {"kappa", 3.1}};
  const Model model = make_model("ggx-conductor+turquin-f", params);
  const fresnel::Channel wrong{.kind = fresnel::Kind::dielectric, .eta = 0.2};
  const CompensationInputs in{model.compensated()->table->at(0.5), model.compensated()->table->e_avg,
                              analysis::albedo(make_model("ggx-conductor", params), std::acos(0.5)).value, wrong(0.5),
                              wrong(1.0), analysis::fresnel_average(wrong).value};
  EXPECT_GT(std::abs(analysis::albedo(model, std::acos(0.5)).value - compensated_albedo(Compensation::turquin_fresnel, in)),
            1e-3);
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
