// `check --sampling` passes every model's sampler, built-in and user-written, at the default
// parameters and at narrow and broad ones — and fails samplers broken on purpose, each in the way
// one of its checks is there to catch.
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <numbers>

#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"
#include "model_ids.h"
#include "specula/sampling/check.h"

namespace specula::sampling {
namespace {

SamplingCheckOptions test_options() {
  SamplingCheckOptions o;
  o.samples = 250'000;  // the CLI's default is 1e6; a quarter keeps the sanitizer build quick
  return o;
}

std::string failures(const SamplingCheck& c) {
  std::string text = c.method + ":";
  for (const AngleCheck& a : c.angles)
    if (!a.passes())
      text += " θ_i=" + std::to_string(a.theta_deg) + " (p=" + std::to_string(a.p_value) +
              ", mean " + std::to_string(a.mean_weight) + " vs " + std::to_string(a.albedo) + " ± " +
              std::to_string(a.standard_error) + ", ∫pdf " + std::to_string(a.pdf_integral) + ", outside " +
              std::to_string(a.outside) + ", uncovered " + std::to_string(a.uncovered_nodes) + ")";
  return text;
}

class EveryModelCheck : public testing::TestWithParam<std::string> {};

TEST_P(EveryModelCheck, PassesTheSamplingCheck) {
  const Sampler sampler(make_model(GetParam()));
  const SamplingCheck c = check_sampling(sampler, test_options());
  EXPECT_TRUE(c.passes()) << failures(c);
  EXPECT_EQ(c.angles.size(), 5u);
}



INSTANTIATE_TEST_SUITE_P(Models, EveryModelCheck, testing::ValuesIn(every_model_id()),
                         [](const auto& info) { return test_name(info.param); });

struct Case {
  std::string id;
  ParamValues params;
  std::optional<Form> form;

  friend void PrintTo(const Case& c, std::ostream* os) {
    *os << c.id;
    for (const auto& [name, value] : c.params) *os << ' ' << name << '=' << value;
    if (c.form) *os << " form " << to_string(*c.form);
  }
};

class Extremes : public testing::TestWithParam<Case> {};

TEST_P(Extremes, PassTheSamplingCheck) {
  const Sampler sampler(make_model(GetParam().id, GetParam().params, GetParam().form));
  const SamplingCheck c = check_sampling(sampler, test_options());
  EXPECT_TRUE(c.passes()) << failures(c);
}

INSTANTIATE_TEST_SUITE_P(
    NarrowAndBroad, Extremes,
    testing::Values(Case{"phong-normalized", {{"n", 1e4}}, {}}, Case{"phong-normalized", {{"n", 0.2}}, {}},
                    Case{"blinn-phong-normalized", {{"n", 5e3}}, {}}, Case{"log-normalized", {{"n", 1e4}}, {}},
                    Case{"log-normalized", {{"n", 0.3}}, {}}, Case{"log-normalized", {{"n", 20}}, Form::nh},
                    Case{"schlick-normalized", {{"n", 2000}}, {}}, Case{"gauss", {{"n", 3000}}, {}},
                    Case{"ggx", {{"alpha", 0.01}}, {}}, Case{"ggx", {{"alpha", 1}}, {}},
                    Case{"cook-torrance", {{"m", 0.05}}, {}}, Case{"ward", {{"alpha", 0.02}}, {}},
                    Case{"my-ggx", {{"alpha", 0.05}}, {}}, Case{"lobe: c^n", {{"n", 3000}}, {}},
                    // The compensations' samplers (models/compensated.h): added, and scaled (ω_i the viewer).
                    Case{"ggx+kulla-conty", {{"f0", 0.5}}, {}}, Case{"ggx+turquin-f", {{"alpha", 0.8}, {"f0", 0.2}}, {}}),
    [](const auto& info) { return "case" + std::to_string(info.index); });

// Negative controls: a sampler broken in one way, and the check that must catch it.

struct Broken {
  Model model = make_model("phong-normalized");
  Sampler right{model};
  SamplerUnderTest test = SamplerUnderTest::of(right);
};

SamplingCheckOptions quick() {
  SamplingCheckOptions o = test_options();
  o.theta_deg = {0, 45, 85};
  return o;
}

TEST(BrokenSampler, PdfOffByAFactorFailsChiSquare) {
  Broken b;
  b.test.pdf = [&](const Vec3& wi, const Vec3& wo) { return 1.05 * b.right.pdf(wi, wo); };
  b.test.sample = [&](const Vec3& wi, double u1, double u2) {
    Sample s = b.right.sample(wi, u1, u2);
    s.pdf *= 1.05, s.weight /= 1.05;  // consistent with the wrong pdf: only χ² and ∫pdf can tell
    return s;
  };
  const SamplingCheck c = check_sampling(b.test, quick());
  EXPECT_FALSE(c.passes());
  EXPECT_FALSE(c.angles[0].chi2_passes());
  EXPECT_FALSE(c.angles[0].pdf_normalized());
  EXPECT_EQ(c.angles[0].weight_mismatches, 0u);
}

TEST(BrokenSampler, MisScaledLobeFailsChiSquare) {
  // Samples from n = 20, densities and weights as if n were 23.
  Broken b;
  const Sampler wider(make_model("phong-normalized", {{"n", 23}}));
  b.test.pdf = [&](const Vec3& wi, const Vec3& wo) { return wider.pdf(wi, wo); };
  b.test.sample = [&](const Vec3& wi, double u1, double u2) {
    Sample s = b.right.sample(wi, u1, u2);
    if (s.valid()) s.pdf = wider.pdf(wi, s.wo), s.weight = b.model({0, 0, 1}, wi, s.wo) * s.wo.z / s.pdf;
    return s;
  };
  const SamplingCheck c = check_sampling(b.test, quick());
  for (const AngleCheck& a : c.angles) EXPECT_FALSE(a.chi2_passes()) << a.theta_deg << "°, p = " << a.p_value;
  EXPECT_TRUE(c.angles[0].pdf_normalized()) << "a normalized pdf, just not the samples'";
}

TEST(BrokenSampler, WrongWeightIsCaught) {
  Broken b;
  b.test.sample = [&](const Vec3& wi, double u1, double u2) {
    Sample s = b.right.sample(wi, u1, u2);
    s.weight *= 1.01;
    return s;
  };
  const SamplingCheck c = check_sampling(b.test, quick());
  EXPECT_GT(c.angles[0].weight_mismatches, 0u);
  EXPECT_TRUE(c.angles[0].chi2_passes()) << "the directions are right";
  EXPECT_FALSE(c.passes());
}

TEST(BrokenSampler, TruncatedLobeFailsCoverageAndAlbedo) {
  // The lobe sampled (and its pdf renormalized) within 20° of R only: pdf = 0 where f > 0.
  Broken b;
  const double cos_cut = std::cos(20 * std::numbers::pi / 180);
  auto r_dot = [](const Vec3& wi, const Vec3& wo) { return -wi.x * wo.x - wi.y * wo.y + wi.z * wo.z; };
  const double kept = 1 - std::pow(cos_cut, 21.0);  // the mass of (n+1)/(2π) c^n within the cut
  b.test.pdf = [&](const Vec3& wi, const Vec3& wo) { return r_dot(wi, wo) >= cos_cut ? b.right.pdf(wi, wo) / kept : 0; };
  b.test.sample = [&](const Vec3& wi, double u1, double u2) {
    Sample s = b.right.sample(wi, u1 * kept, u2);
    if (s.valid()) s.pdf = b.test.pdf(wi, s.wo), s.weight = b.model({0, 0, 1}, wi, s.wo) * s.wo.z / s.pdf;
    return s;
  };
  SamplingCheckOptions o = quick();
  o.theta_deg = {0};
  const SamplingCheck c = check_sampling(b.test, o);
  EXPECT_GT(c.angles[0].uncovered_nodes, 0u);
  EXPECT_FALSE(c.angles[0].albedo_agrees()) << c.angles[0].mean_weight << " vs " << c.angles[0].albedo;
}

TEST(BrokenSampler, SamplesBelowTheHorizonAreCaught) {
  Broken b;
  b.test.sample = [&](const Vec3& wi, double u1, double u2) {
    Sample s = b.right.sample(wi, u1, u2);
    if (u2 < 0.01) s = {Vec3{0, 0.6, -0.8}, 1, 1};
    return s;
  };
  const SamplingCheck c = check_sampling(b.test, quick());
  EXPECT_GT(c.angles[0].outside, 0u);
  EXPECT_FALSE(c.passes());
}

// Issue 23: a negative model is what the check exists to report. It fails at the first angle
// where a sample has f < 0 and checks nothing further (before, the cubature refined its cells
// toward a "peak" 1e-6 wide — the half maximum of a negative f — without end).
TEST(SamplingCheck, ANegativeModelFailsAtOnceAndStops) {
  SamplingCheckOptions o;
  o.samples = 1000;
  o.theta_deg = {0, 30, 60};
  const SamplingCheck negative = check_sampling(Sampler(make_model("brdf: -nl")), o);
  ASSERT_EQ(negative.angles.size(), 1u);
  EXPECT_EQ(negative.angles[0].negative_samples, o.samples);  // cosine-weighted; f = −cos θ_i everywhere
  EXPECT_EQ(negative.angles[0].min_f, -1);
  EXPECT_FALSE(negative.passes());
  const SamplingCheck positive = check_sampling(Sampler(make_model("brdf: nl")), o);  // the control
  ASSERT_EQ(positive.angles.size(), 3u);
  for (const AngleCheck& a : positive.angles) EXPECT_EQ(a.negative_samples, 0u);
  EXPECT_TRUE(positive.passes()) << failures(positive);
}

// Issue 23: so is a model that is inf or NaN (before, the albedo's quadrature bisected the
// non-finite integrand without end). `brdf: 1e308` is finite but its albedo is not: the check
// then runs to its end and fails on the albedo.
TEST(SamplingCheck, ANonFiniteModelFailsAtOnceAndStops) {
  SamplingCheckOptions o;
  o.samples = 1000;
  o.theta_deg = {0, 30};
  for (const char* model : {"brdf: 1/(nl-nl)", "brdf: sqrt(-nl)", "lobe: 1/(c-c)"}) {
    const SamplingCheck c = check_sampling(Sampler(make_model(model)), o);
    ASSERT_EQ(c.angles.size(), 1u) << model;
    EXPECT_EQ(c.angles[0].non_finite_samples, o.samples) << model;
    EXPECT_FALSE(c.passes()) << model;
  }
  const SamplingCheck overflow = check_sampling(Sampler(make_model("brdf: 1e308")), o);
  ASSERT_EQ(overflow.angles.size(), 2u);
  EXPECT_FALSE(std::isfinite(overflow.angles[0].albedo));
  EXPECT_FALSE(overflow.passes());
  const SamplingCheck control = check_sampling(Sampler(make_model("brdf: 1/(nl-nl+1)")), o);
  for (const AngleCheck& a : control.angles) EXPECT_EQ(a.non_finite_samples, 0u);
  EXPECT_TRUE(control.passes()) << failures(control);
}

// Ctrl-C (or a deadline) reaches the χ² cubature inside a row of cells, not only between rows:
// one thread, a cancel a hundred pdf calls into the first row (of ~5000), and what follows it.
TEST(SamplingCheck, AStopInsideTheCubatureEndsItWithinOneRefinement) {
  const Sampler lambert(make_model("lambert"));
  SamplerUnderTest test = SamplerUnderTest::of(lambert);
  constexpr std::size_t kSamples = 1000, kStopAt = kSamples + 100;  // the tally's calls, then the cubature's
  std::atomic<bool> cancel{false};
  std::size_t calls = 0, after_stop = 0;
  test.pdf = [&](const Vec3& wi, const Vec3& wo) {
    if (++calls == kStopAt) cancel = true;
    if (cancel) ++after_stop;
    return lambert.pdf(wi, wo);
  };
  SamplingCheckOptions o;
  o.samples = kSamples;
  o.theta_deg = {0};
  tbb::task_arena one_thread(1);
  const ScopedLimit limit(WorkLimit{std::chrono::steady_clock::time_point::max(), &cancel});
  one_thread.execute([&] { EXPECT_THROW(check_sampling(test, o), Interrupted); });
  EXPECT_LT(after_stop, 200u);  // what a refinement had left (≤ 4 × 16 calls), and the next cell's rule
  calls = after_stop = 0;
  cancel = false;
  const ScopedLimit never(WorkLimit{std::chrono::steady_clock::time_point::max(), nullptr});
  one_thread.execute([&] { EXPECT_TRUE(check_sampling(test, o).passes()); });
  EXPECT_GT(after_stop, 32u * 64 * 16);  // the control: without a stop, every cell of every row
}

TEST(SamplingCheck, AnglesAreSidakCorrected) {
  const SamplingCheck c = check_sampling(Sampler(make_model("lambert")), quick());
  EXPECT_NEAR(c.angles[0].alpha, 1 - std::pow(0.99, 1.0 / 3), 1e-15);
}

TEST(SamplingCheck, RejectsBadOptions) {
  const Sampler sampler(make_model("lambert"));
  SamplingCheckOptions o;
  o.theta_deg = {90};
  EXPECT_THROW(check_sampling(sampler, o), InvalidArgument);
  o = {};
  o.theta_deg = {};
  EXPECT_THROW(check_sampling(sampler, o), InvalidArgument);
  o = {};
  o.samples = 10;
  EXPECT_THROW(check_sampling(sampler, o), InvalidArgument);
  o = {};
  o.cos_bins = 1000;
  EXPECT_THROW(check_sampling(sampler, o), InvalidArgument);
}

}  // namespace
}  // namespace specula::sampling
