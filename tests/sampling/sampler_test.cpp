// The samplers' parts against independent references: the log lobe's closed-form CDF against
// Gauss-Kronrod quadrature, the radial densities integrating to 1, every sample's pdf and weight
// against pdf() and the model, the tables' stated error, and seeded sequences independent of the
// thread count.
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <tbb/global_control.h>

#include "radial.h"
#include "specula/catalogue/catalogue.h"
#include "specula/families/families.h"
#include "model_ids.h"
#include "specula/sampling/sampler.h"

namespace specula::sampling {
namespace {

constexpr double kPi = std::numbers::pi;
const Vec3 kNormal{0, 0, 1};

double quadrature(const auto& f, double a, double b) {
  return boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, a, b, 15, 1e-15);
}

TEST(LogRadial, ClosedFormCdfMatchesQuadratureForEveryN) {
  for (double n : {1e-3, 0.1, 0.5, 0.69, 0.7, 1.0, 20.0, 1e3, 1e6, 1e9}) {
    const LogRadial radial(n);
    const double b = std::numbers::ln2 / n;
    for (double t : {1e-6, 0.01, 0.5, 1.0, 2.0, 2.999, 3.0}) {
      const double reference =
          quadrature([b](double s) { return (1 - 0.5 * std::log2(1 + s)) * std::exp(-b * s); }, 0, t);
      // What Newton needs: the sampled u off by ≤ 1e-14 (of the total), the relative error small.
      EXPECT_NEAR(radial.cdf_integral(t), reference, 1e-14 * radial.cdf_integral(3) + 1e-10 * reference)
          << "n = " << n << ", t = " << t;
    }
  }
}

/// ∫ p over the sphere around the axis = 2π ∫₀^∞ p(y) e^(−y) dy (dω = x dy dφ, x = e^(−y)).
template <class Radial>
double total_mass(const Radial& radial, double end) {
  return 2 * kPi * quadrature([&](double y) { return radial.density(y) * std::exp(-y); }, 0, end);
}

/// A power-cosine density with the wrong normalization, (n + 2)/(2π) cos^n.
struct MisnormalizedPower {
  double n;
  double density(double y) const { return (n + 2) / (2 * kPi) * std::exp(-n * y); }
};

TEST(Radial, DensitiesIntegrateToOne) {
  EXPECT_NEAR(total_mass(PowerRadial(20), 50), 1, 1e-12);
  EXPECT_NEAR(total_mass(PowerRadial(1e4), 0.05), 1, 1e-10);
  EXPECT_NEAR(total_mass(BeckmannRadial(0.3), 20), 1, 1e-12);
  EXPECT_NEAR(total_mass(LogRadial(20), 3 * std::numbers::ln2 / 20), 1, 1e-12);
  EXPECT_NEAR(total_mass(LogRadial(0.01), 3 * std::numbers::ln2 / 0.01), 1, 1e-12);
  // Negative control: the same integral of a power-cosine density normalized by (n + 2)/(2π),
  // the half vector's factor where ω_o's is (n + 1)/(2π), finds its mass (n + 2)/(n + 1).
  EXPECT_NEAR(total_mass(MisnormalizedPower{20}, 50), 22.0 / 21, 1e-12);
}

/// The fraction of samples with y ≤ y_q against the density's mass up to y_q.
template <class Radial>
void expect_samples_follow(const Radial& radial, double y_q) {
  const double mass = 2 * kPi * quadrature([&](double y) { return radial.density(y) * std::exp(-y); }, 0, y_q);
  constexpr int kCount = 200'000;
  int below = 0;
  for (int i = 0; i < kCount; ++i) {
    const PolarAngle a = radial.sample((i + 0.5) / kCount);  // stratified: error ~ 1/kCount
    below += -std::log(a.cos) <= y_q;
  }
  EXPECT_NEAR(double(below) / kCount, mass, 2e-5);
}

TEST(Radial, InverseCdfsInvertTheirDensities) {
  for (double n : {0.5, 20.0, 1e4}) {
    expect_samples_follow(PowerRadial(n), std::numbers::ln2 / n);
    expect_samples_follow(LogRadial(n), 1.5 * std::numbers::ln2 / n);
  }
  expect_samples_follow(BeckmannRadial(0.2), 0.01);
  const lobes::Schlick<double> schlick{50};
  const TableRadial table([&](double y) { return schlick.at_log_cos(y); }, schlick.half_max_log_cos(), 16);
  expect_samples_follow(table, 0.01);
}

TEST(Radial, PowerSampleKeepsTheAngleOfNarrowLobes) {
  // n = 1e9: 1 − cos underflows in double, the sine does not. u = ½: cos = 2^(−1/(n+1)), so
  // y = ln 2/(n + 1) and sin = √(1 − e^(−2y)) = √(2y)(1 − y/2 + O(y²)).
  const PolarAngle a = PowerRadial(1e9).sample(0.5);
  const double y = std::log(2.0) / (1e9 + 1);
  EXPECT_NEAR(a.sin, std::sqrt(2 * y) * (1 - y / 2), 1e-14 * a.sin);
}

TEST(TableRadial, StatedErrorHoldsOverTheExponents) {
  // docs/sampling.md: the tables' L1 error is below 2e-3 for the built-in tabulated lobes.
  for (const families::Family* family : families::kFamilies) {
    if (family->kind != ModelKind::lobe || family->sampling != Method::tabulated) continue;
    for (double n : {0.5, 2.0, 20.0, 1e3, 1e6}) {
      const Sampler sampler(make_model(family->models[0].id, {{"n", n}}));
      EXPECT_LT(sampler.table_error(), 2e-3) << family->name << " n = " << n;
      EXPECT_GT(sampler.table_error(), 0) << family->name;
    }
  }
}

class EveryModelSampler : public testing::TestWithParam<std::string> {};

TEST_P(EveryModelSampler, SamplesCarryTheirPdfAndWeight) {
  const Model model = make_model(GetParam());
  const Sampler sampler(model);
  for (double theta : {0.0, 0.7, 1.45}) {
    const Vec3 wi{std::sin(theta), 0, std::cos(theta)};
    int valid = 0;
    for (const Sample& s : draw_samples(sampler, wi, 2000, 3)) {
      if (!s.valid()) {
        EXPECT_EQ(s.weight, 0);
        continue;
      }
      ++valid;
      EXPECT_GT(s.wo.z, 0);
      EXPECT_NEAR(std::hypot(s.wo.x, s.wo.y, s.wo.z), 1, 1e-12);
      EXPECT_DOUBLE_EQ(s.pdf, sampler.pdf(wi, s.wo));
      EXPECT_NEAR(s.weight, model(kNormal, wi, s.wo) * s.wo.z / s.pdf, 1e-12 * s.weight);
      const ValuePdf v = sampler.eval_pdf(wi, s.wo);
      EXPECT_EQ(v.pdf, s.pdf);
      EXPECT_EQ(v.f, model(kNormal, wi, s.wo));
    }
    EXPECT_GT(valid, 500) << "θ_i = " << theta;
  }
  EXPECT_EQ(sampler.pdf(Vec3{0, 0, 1}, Vec3{0.6, 0, -0.8}), 0) << "below the horizon";
}


INSTANTIATE_TEST_SUITE_P(Models, EveryModelSampler, testing::ValuesIn(every_model_id()),
                         [](const auto& info) { return test_name(info.param); });

TEST(Sampler, MethodsAreTheFamiliesOwn) {
  EXPECT_EQ(Sampler(make_model("phong")).method(), Method::power_cosine);
  EXPECT_EQ(Sampler(make_model("log-normalized")).method(), Method::log_t_space);
  EXPECT_EQ(Sampler(make_model("ggx")).method(), Method::ggx_visible_normals);
  EXPECT_EQ(Sampler(make_model("ward")).method(), Method::beckmann);
  EXPECT_EQ(Sampler(make_model("lambert")).method(), Method::cosine);
  EXPECT_EQ(Sampler(make_model("lobe: c^n", {{"n", 5}})).method(), Method::tabulated);
  EXPECT_EQ(Sampler(make_model("phong")).cosine_share(), 0);
  EXPECT_GT(Sampler(make_model("lobe: c^n", {{"n", 5}})).cosine_share(), 0);
}

TEST(Sampler, ZeroLobeFallsBackToCosine) {
  const Sampler sampler(make_model("brdf: 0*nl"));
  EXPECT_EQ(sampler.cosine_share(), 1);
  EXPECT_NEAR(sampler.pdf({0, 0, 1}, {0, 0, 1}), 1 / kPi, 1e-15);
}

TEST(DrawSamples, TheSameForAnyThreadCount) {
  const Sampler sampler(make_model("log-normalized"));
  const Vec3 wi{0.5, 0, std::sqrt(0.75)};
  std::vector<Sample> one, many = draw_samples(sampler, wi, 200'000, 9);
  {
    const tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = draw_samples(sampler, wi, 200'000, 9);
  }
  ASSERT_EQ(one.size(), many.size());
  for (std::size_t i = 0; i < one.size(); ++i) ASSERT_EQ(one[i].wo.x, many[i].wo.x) << i;
  EXPECT_NE(draw_samples(sampler, wi, 10, 10)[0].wo.x, many[0].wo.x) << "another seed, other samples";
}

}  // namespace
}  // namespace specula::sampling
