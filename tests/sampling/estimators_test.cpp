// BRDF Explorer's albedo estimators (sampling/estimators.h): each unbiased, within 4 standard
// errors of the cubature (analysis/albedo.h, 8+ digits) for lobes, microfacet BRDFs and Lambert;
// the control holds them to the cubature at another angle, which they miss.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "specula/analysis/albedo.h"
#include "specula/catalogue/catalogue.h"
#include "specula/sampling/estimators.h"

namespace specula::sampling {
namespace {

constexpr Estimator kEstimators[] = {Estimator::uniform, Estimator::cosine, Estimator::sampler, Estimator::mis};
constexpr double kDegree = 3.14159265358979323846 / 180;

TEST(Estimators, EachIsTheCubaturesAlbedoWithinItsError) {
  const Model models[] = {make_model("ggx", {{"alpha", 0.3}}), make_model("log-normalized", {{"n", 20}}),
                          make_model("lambert"), make_model("beckmann-conductor", {{"alpha", 0.5}})};
  for (const Model& m : models)
    for (const double deg : {0.0, 60.0}) {
      const double exact = analysis::albedo(m, deg * kDegree).value;
      for (const Estimator e : kEstimators) {
        const AlbedoEstimate a = albedo_estimate(m, deg * kDegree, e, 100'000, 7);
        // Lambert by the cosine (or a sampler that is the cosine): exact, with no variance.
        EXPECT_NEAR(a.mean, exact, 4 * a.standard_error + 1e-12) << m.id() << " " << deg << " " << to_string(e);
      }
    }
}

TEST(Estimators, AreDeterministicAndTheSamplerBeatsUniformOnANarrowLobe) {
  const Model narrow = make_model("log-normalized", {{"n", 200}});
  const AlbedoEstimate a = albedo_estimate(narrow, 0.5, Estimator::sampler, 20'000, 3);
  const AlbedoEstimate b = albedo_estimate(narrow, 0.5, Estimator::sampler, 20'000, 3);
  EXPECT_EQ(a.mean, b.mean);
  EXPECT_LT(a.standard_error, albedo_estimate(narrow, 0.5, Estimator::uniform, 20'000, 3).standard_error / 5);
}

TEST(Estimators, ControlTheAlbedoAtAnotherAngleIsMissed) {
  const Model ggx = make_model("ggx", {{"alpha", 0.3}, {"f0", 0.04}});
  const double elsewhere = analysis::albedo(ggx, 80 * kDegree).value;
  for (const Estimator e : kEstimators) {
    const AlbedoEstimate a = albedo_estimate(ggx, 0, e, 100'000, 7);
    EXPECT_GT(std::abs(a.mean - elsewhere), 4 * a.standard_error) << to_string(e);
  }
}

}  // namespace
}  // namespace specula::sampling
