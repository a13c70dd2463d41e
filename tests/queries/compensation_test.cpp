// The compensations' albedos (queries/compensation.h) and the verdict that measures them against
// the random walk: each closed form against the same arithmetic written out, all of them 1 where
// F = 1 (the energy they exist to restore), and the verdict's plumbing on a grid where the truth
// is known (F = 1: the walk's total is 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "specula/analysis/fresnel.h"
#include "specula/exceptions.h"
#include "specula/queries/compensation.h"

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
      for (std::size_t c = 1; c < kCompensationCount; ++c)
        EXPECT_NEAR(compensated_albedo(Compensation(c), white), 1, 1e-15) << kCompensationNames[c];
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
  // The verdict's plumbing: with F = 1 the walk's total is 1, which every compensation gives; only
  // `none` misses, by 1 − E(μ).
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
    EXPECT_LT(sum.max_error, 4 * sum.max_walk_error + 1e-6) << kCompensationNames[std::size_t(sum.compensation)];
  }
  const io::Table t = summary_table(v);
  EXPECT_EQ(t.rows.size(), kCompensationCount);
  s.alpha.clear();
  EXPECT_THROW(verdict(s), InvalidArgument);
}

}  // namespace
}  // namespace specula::queries
