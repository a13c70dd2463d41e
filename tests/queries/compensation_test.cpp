// The compensations' albedos (queries/compensation.h) and the verdict that measures them against
// the random walk: each closed form against the same arithmetic written out, all of them 1 where
// F = 1 (the energy they exist to restore), and the verdict's plumbing on a grid where the truth
// is known (F = 1: the walk's total is 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "specula/analysis/albedo.h"
#include "specula/analysis/fresnel.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/queries/compensation.h"
#include "specula/walk/walk.h"

namespace specula::queries {
namespace {

TEST(Compensation, EachFormulaAtOnePoint) {
  const CompensationInputs in{0.6, 0.7, 0.3, 0.55, 0.5, 0.52};
  const double fms = 0.52 * 0.7 / (1 - 0.52 * 0.3);
  EXPECT_DOUBLE_EQ(compensated_albedo(Compensation::none, in), 0.3);
  EXPECT_DOUBLE_EQ(compensated_albedo(Compensation::kulla_conty, in), 0.3 + 0.4 * 0.52 * 0.52 * 0.7 / (1 - 0.52 * 0.3));
  EXPECT_DOUBLE_EQ(compensated_albedo(Compensation::turquin_f0, in), 0.3 * (1 + 0.5 * 0.4 / 0.6));
  EXPECT_DOUBLE_EQ(compensated_albedo(Compensation::turquin_fresnel, in), 0.3 * (1 + 0.55 * 0.4 / 0.6));
  EXPECT_DOUBLE_EQ(compensated_albedo(Compensation::turquin_average, in), 0.3 * (1 + 0.52 * 0.4 / 0.6));
  EXPECT_DOUBLE_EQ(compensated_albedo(Compensation::cycles, in), 0.3 * (1 + fms * 0.4 / 0.6));
  const double single = 0.3 / 0.6, first = std::max(single, 0.52), later = (single + 0.52) / 2, p = std::pow(0.7, 0.7);
  EXPECT_DOUBLE_EQ(compensated_albedo(Compensation::walk_fit, in), 0.3 + 0.4 * first * later * p / (1 - later * (1 - p)));
}

TEST(Compensation, EveryOneRestoresAWhiteFurnace) {
  for (double e : {0.3, 0.8, 0.99})
    for (double e_avg : {0.4, 0.9}) {
      const CompensationInputs white{e, e_avg, e, 1, 1, 1};
      EXPECT_LT(compensated_albedo(Compensation::none, white), 1);  // the control: it loses energy
      for (std::size_t c = 1; c < kCompensationCount; ++c) {
        if (Compensation(c) == Compensation::shipped) continue;  // a model's albedo, not a formula in these inputs
        EXPECT_NEAR(compensated_albedo(Compensation(c), white), 1, 1e-15) << kCompensationNames[c];
      }
    }
}

TEST(Compensation, TheVerdictsFresnelsAreInTheirDomains) {
  const auto fresnels = verdict_fresnels();
  ASSERT_EQ(fresnels.size(), 4u + 3u + 9u);
  for (const auto& f : fresnels) EXPECT_EQ(analysis::fresnel_domain_error(f.channel), "") << f.label;
  // Gold reflects red more than blue at normal incidence, aluminium about 0.9 in every channel.
  EXPECT_GT(fresnels[7].channel(1.0), fresnels[9].channel(1.0));
  for (int k = 13; k < 16; ++k) EXPECT_NEAR(fresnels[k].channel(1.0), 0.91, 0.05) << fresnels[k].label;
}

TEST(Compensation, AgainstAWhiteWalkEveryCompensationIsWithinItsError) {
  // The verdict's plumbing: with F = 1 the walk's total is 1, which every compensation gives (`+ms`
  // too, as ggx+ms at F0 = 1); only `none` misses, by 1 − E(μ).
  VerdictSettings s;
  s.alpha = {0.3, 1.0};
  s.mu = {0.2, 1.0};
  s.fresnels = {{"white", "one", fresnel::Channel{}}};
  s.paths = walk::kMinPaths;
  const Verdict v = verdict(s);
  ASSERT_EQ(v.cells.rows.size(), 4u);
  ASSERT_EQ(v.summary.size(), kCompensationCount);
  for (const auto& sum : v.summary) {
    if (sum.compensation == Compensation::none) {
      EXPECT_GT(sum.max_error, 0.3);  // α = 1 at normal incidence loses 69 %
      continue;
    }
    EXPECT_EQ(sum.cells, 4u) << kCompensationNames[std::size_t(sum.compensation)];  // every one applies
    EXPECT_LT(sum.max_error, 4 * sum.max_walk_error + 1e-6) << kCompensationNames[std::size_t(sum.compensation)];
  }
  const io::Table t = summary_table(v);
  EXPECT_EQ(t.rows.size(), kCompensationCount);
  s.alpha.clear();
  EXPECT_THROW(verdict(s), InvalidArgument);
}

// `ggx+ms` at F0 < 1 gives back the random walk's own multiply scattered albedo (the table of
// scripts/make_walk_ms_table), so its albedo is the walk's within the table's stated error, which
// is within the 0.01 issue 39 asks for. Checked against fresh walks (seed 3, 2^15 paths a cell,
// about 2 s under the sanitizers) off the table's nodes, at the cells where the published
// compensations miss most (docs/energy-compensation.md). The control: the verdict's best
// published formula for Schlick (`cycles`) fails the same check at the smooth grazing cell.
// `+ms` on GGX with another Fresnel kind reads the walk's table at the Schlick F0 of the same F_avg
// (analysis::walk_equivalent_f0): within the verdict's largest error over its families (0.0153,
// docs/energy-compensation.md) of the walk with that Fresnel itself, and far closer for a dielectric
// at moderate angles, where Kulla-Conty's F_ms misses (the control).
TEST(Compensation, MsForAnotherFresnelKindIsTheWalksAtTheSameAverage) {
  struct Cell {
    std::string id;
    ParamValues params;
    fresnel::Channel channel;
    double mu, tolerance;
  };
  using fresnel::Kind;
  const Cell glass{"ggx-dielectric", {{"alpha", 0.5}, {"eta", 1.5}}, {.kind = Kind::dielectric, .eta = 1.5}, 0.5, 1e-3};
  const Cell cells[] = {
      glass,
      {"ggx-conductor", {{"alpha", 1}, {"eta", 0.143}, {"kappa", 3.983}}, {.kind = Kind::conductor, .eta = 0.143, .kappa = 3.983}, 1, 0.016},
      {"ggx-f82", {{"alpha", 0.3}, {"f0", 0.9}, {"tint", 0.95}}, {.kind = Kind::f82_tint, .f0 = 0.9, .tint = 0.95}, 0.7, 0.016},
      {"ggx-schlick", {{"alpha", 0.7}, {"f0", 0.2}, {"f90", 0.9}, {"exponent", 4}},
       {.kind = Kind::schlick, .f0 = 0.2, .f90 = 0.9, .exponent = 4}, 0.3, 0.016}};
  const auto walk_total = [](const Cell& c) {
    walk::Options o;
    o.paths = walk::kMinPaths;
    o.seed = 3;
    return walk::conductor_albedo({walk::Distribution::ggx, c.params.at("alpha")}, {&c.channel, 1}, c.mu, o)[0].total;
  };
  for (const Cell& c : cells) {
    const Model ms = make_model(c.id + "+ms", c.params);
    ASSERT_TRUE(ms.compensated()->table->from_walk) << c.id;
    const walk::Estimate truth = walk_total(c);
    EXPECT_NEAR(analysis::albedo(ms, std::acos(c.mu)).value, truth.value, c.tolerance + 4 * truth.error) << c.id;
  }
  const walk::Estimate truth = walk_total(glass);
  const double kulla_conty = analysis::albedo(make_model("ggx-dielectric+kulla-conty", glass.params), std::acos(glass.mu)).value;
  EXPECT_GT(std::abs(kulla_conty - truth.value), glass.tolerance + 4 * truth.error);
}

TEST(Compensation, GgxMsAtF0BelowOneIsTheWalksAlbedo) {
  struct Cell {
    double alpha, mu, f0;
  };
  const auto walk_total = [](const Cell& c) {
    const fresnel::Channel f{fresnel::Kind::schlick, c.f0};
    walk::Options o;
    o.paths = walk::kMinPaths;
    o.seed = 3;
    return walk::conductor_albedo({walk::Distribution::ggx, c.alpha}, {&f, 1}, c.mu, o)[0].total;
  };
  const Cell smooth_grazing{0.05, 0.05, 0.04};
  for (const Cell c : {smooth_grazing, Cell{0.3, 1, 0.04}, Cell{1, 1, 0.04}, Cell{1, 0.5, 0.5}, Cell{0.5, 0.7, 0.9},
                       Cell{0.1, 0.17, 0.2}, Cell{0.72, 0.3, 0.33}}) {
    SCOPED_TRACE(testing::Message() << "alpha " << c.alpha << ", mu " << c.mu << ", F0 " << c.f0);
    const Model ms = make_model("ggx+ms", {{"alpha", c.alpha}, {"f0", c.f0}});
    const EnergyTable& table = *ms.compensated()->table;
    ASSERT_TRUE(table.from_walk);
    EXPECT_LE(table.albedo_error, 0.01);
    const walk::Estimate truth = walk_total(c);
    EXPECT_NEAR(analysis::albedo(ms, std::acos(c.mu)).value, truth.value, table.albedo_error + 4 * truth.error);
  }
  const Model white = make_model("ggx+ms", {{"alpha", smooth_grazing.alpha}, {"f0", 1}});
  const Model ggx = make_model("ggx", {{"alpha", smooth_grazing.alpha}, {"f0", smooth_grazing.f0}});
  const fresnel::Channel f{fresnel::Kind::schlick, smooth_grazing.f0};
  const EnergyTable& e = *white.compensated()->table;
  const CompensationInputs in{e.at(smooth_grazing.mu), e.e_avg, analysis::albedo(ggx, std::acos(smooth_grazing.mu)).value,
                              f(smooth_grazing.mu), smooth_grazing.f0, analysis::fresnel_average(f).value};
  const walk::Estimate truth = walk_total(smooth_grazing);
  EXPECT_GT(std::abs(compensated_albedo(Compensation::cycles, in) - truth.value), 0.01 + 4 * truth.error);
  EXPECT_FALSE(white.compensated()->table->from_walk) << "F0 = 1: the cubature's white table, albedo 1";
}

// The verdict measures what ships where it applies (Schlick's F0): within the table's stated error of
// the walk at the grid's corners, where the best published formula for Schlick misses by more.
TEST(Compensation, TheVerdictMeasuresWhatShips) {
  VerdictSettings s;
  s.alpha = {0.05, 1.0};
  s.mu = {0.05, 1.0};
  s.fresnels = {verdict_fresnels()[0]};  // Schlick F0 = 0.04
  s.paths = walk::kMinPaths;
  const Verdict v = verdict(s);
  const auto summary = [&](Compensation c) {
    return *std::find_if(v.summary.begin(), v.summary.end(), [&](const auto& sum) { return sum.compensation == c; });
  };
  const VerdictSummary shipped = summary(Compensation::shipped), cycles = summary(Compensation::cycles);
  EXPECT_EQ(shipped.cells, 4u);
  const double stated = make_model("ggx+ms", {{"f0", 0.04}}).compensated()->table->albedo_error;
  EXPECT_LE(shipped.max_error, stated + 4 * shipped.max_walk_error);
  EXPECT_GT(cycles.max_error, stated + 4 * cycles.max_walk_error);  // the control
}

// The other models with a Fresnel (Cook-Torrance's Schlick F0) ship the verdict's `kulla-conty`:
// the white table (one for every F0) and F_ms from F0's F_avg. Checked against the formula on
// inputs computed apart (the white model's cubature albedo, F_avg's closed form); the control,
// the white lobe's lost energy all given back (F_ms = 1, what M+ms did before it knew of
// Fresnel), misses by far more than the table's error.
TEST(Compensation, CookTorranceMsAtF0BelowOneIsKullaConty) {
  for (const double f0 : {0.04, 0.5}) {
    const Model ms = make_model("cook-torrance+ms", {{"m", 0.4}, {"f0", f0}});
    const Compensated& parts = *ms.compensated();
    EXPECT_EQ(parts.table, make_model("cook-torrance+ms", {{"m", 0.4}, {"f0", 1}}).compensated()->table);
    const double theta = 1.0;
    const double e = analysis::albedo(make_model("cook-torrance", {{"m", 0.4}, {"f0", 1}}), theta).value;
    const double single = analysis::albedo(*parts.base, theta).value;
    const double f_avg = f0 + (1 - f0) / 21;
    const CompensationInputs in{e, parts.table->e_avg, single, 0, f0, f_avg};
    const double albedo = analysis::albedo(ms, theta).value;
    EXPECT_NEAR(albedo, compensated_albedo(Compensation::kulla_conty, in), parts.table->albedo_error);
    EXPECT_GT(std::abs(single + (1 - e) - albedo), 10 * parts.table->albedo_error);  // the control
  }
}

}  // namespace
}  // namespace specula::queries
