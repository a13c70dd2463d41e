// The random walk on the Smith microsurface (walk.h) proven by its own identities, each with a
// negative control that a faulty walk fails (walk::Faults):
//   1. with F = 1 a conductor reflects everything: total albedo 1 within 3σ (fault: Russian
//      roulette that forgets to reweight its survivors);
//   2. its first bounce is the single-scattering model: order 1 equals the albedo of D·F·G₂ by
//      quadrature (here) and by specula's cubature (GGX) within 3σ (fault: G₁ of a wrong roughness, α × 1.25);
//   3. the multiple-scattering BRDF it estimates is reciprocal within its error (fault: the
//      Fresnel of the second bounce dropped);
//   4. with a constant F = c, order k is c^k times order k at F = 1, path by path (the same fault);
//   5. a rough dielectric conserves energy: reflection + transmission = 1 within 3σ (the roulette
//      fault), and its first bounce reflects and transmits what single scattering does (the wrong
//      G₁).
// Cost under the sanitizers: about 15 s in all (4 s of them the reference quadratures).
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <optional>
#include <vector>

#include "sobol.h"
#include "specula/analysis/albedo.h"
#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"
#include "specula/sampling/seeds.h"
#include "specula/walk/walk.h"

namespace specula::walk {
namespace {

using fresnel::Channel;
using fresnel::Kind;

constexpr double kPi = std::numbers::pi;

Vec3 direction(double mu, double phi) {
  const double s = std::sqrt(1 - mu * mu);
  return {s * std::cos(phi), s * std::sin(phi), mu};
}

Options paths(std::uint64_t n, std::uint64_t seed = 7) {
  Options options;
  options.paths = n;
  options.seed = seed;
  return options;
}

const Channel kOne{};
// Where every path leaves after one bounce (α = 0.05 at normal incidence) the estimate has no
// spread: it is 1 up to the rounding of a few thousand sums.
constexpr double kRounding = 1e-10;
const Channel kSchlick004{Kind::schlick, 0.04, 1, 5};

// --- an independent single-scattering albedo: D, Λ and G₂ from their closed forms ---------------

double ndf(Distribution d, double alpha, double cos_h) {
  const double c2 = cos_h * cos_h, t2 = (1 - c2) / c2, a2 = alpha * alpha;
  if (d == Distribution::ggx) return a2 / (kPi * c2 * c2 * (a2 + t2) * (a2 + t2));
  return std::exp(-t2 / a2) / (kPi * a2 * c2 * c2);
}

double smith_lambda(Distribution d, double alpha, double mu) {
  const double a = mu / (alpha * std::sqrt(1 - mu * mu));
  if (mu >= 1) return 0;
  if (d == Distribution::ggx) return (-1 + std::sqrt(1 + 1 / (a * a))) / 2;
  return (std::exp(-a * a) / (a * std::sqrt(kPi)) - std::erfc(a)) / 2;
}

// ∫ f over the parts of [0, top] where `inside` holds, each part integrated on its own so that the
// rule sees no edge: the edges are found on a grid of 64 cells and bisected to 1e-15 (a part
// narrower than a cell may be missed; the integrands here have one or two parts).
template <class Inside, class F>
double integrate_where(const Inside& inside, const F& f, double top) {
  using boost::math::quadrature::gauss_kronrod;
  constexpr int kCells = 64;
  double total = 0, start = 0;
  bool in = inside(0.0);
  for (int i = 1; i <= kCells; ++i) {
    const double b = top * i / kCells;
    if (inside(b) != in) {
      double lo = top * (i - 1) / kCells, hi = b;
      for (int k = 0; k < 60 && hi - lo > 1e-15; ++k) ((inside((lo + hi) / 2) == in) ? lo : hi) = (lo + hi) / 2;
      if (in) total += gauss_kronrod<double, 31>::integrate(f, start, lo, 10, 1e-10);
      start = hi;
      in = !in;
    }
  }
  if (in) total += gauss_kronrod<double, 31>::integrate(f, start, top, 10, 1e-10);
  return total;
}

// Single scattering by quadrature over the facet normal h (θ_h = atan(α tan(πs/2)) spreads the
// lobe over s ∈ [0, 1)), from the closed forms of D and Λ alone:
//   reflection:   E_R(μ_i) = ∫ F(ω_i·h) D(h) (ω_i·h)/μ_i · 1/(1 + Λ_i + Λ_o) dω_h, ω_o the mirror
//                 direction, above the horizon;
//   transmission: E_T(μ_i) = ∫ (1 − F) D(h) (ω_i·h)/μ_i · B(1 + Λ_i, 1 + Λ_t) dω_h, ω_t the
//                 refracted direction, below the horizon (the first meeting's height has the density
//                 (1 + Λ_i) u^Λ_i, and the refracted ray leaves from 1 − u with (1 − u)^Λ_t: Heitz 2014,
//                 eq. 101, the height-correlated masking-shadowing of transmission, a beta function).
enum class Side { reflection, transmission };

double single_scattering(Distribution d, double alpha, double mu, const Channel& f, Side side = Side::reflection) {
  using boost::math::quadrature::gauss_kronrod;
  const Vec3 wi = direction(mu, 0);
  const double lambda_i = smith_lambda(d, alpha, mu);
  const auto half = [&](double s, double phi) {
    const double theta = std::atan(alpha * std::tan(kPi * s / 2));
    return Vec3{std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
  };
  // The direction leaving the facet h: mirrored, or refracted (none under total reflection).
  const auto leaving = [&](const Vec3& h, double ih) -> std::optional<Vec3> {
    if (ih <= 0) return std::nullopt;
    if (side == Side::reflection) return h * (2 * ih) - wi;
    const double eta = f.eta, sin2_t = (1 - ih * ih) / (eta * eta);
    if (sin2_t >= 1) return std::nullopt;
    return normalized(h * (ih / eta - std::sqrt(1 - sin2_t)) - wi * (1 / eta));
  };
  const auto valid = [&](double s, double phi) {
    const Vec3 h = half(s, phi);
    const auto w = leaving(h, dot(wi, h));
    return w && (side == Side::reflection ? w->z > 0 : w->z < 0);
  };
  const auto masking = [&](const Vec3& h, double ih) {
    const Vec3 w = *leaving(h, ih);
    if (side == Side::reflection) return f(ih) / (1 + lambda_i + smith_lambda(d, alpha, w.z));
    return (1 - f(ih)) * std::beta(1 + lambda_i, 1 + smith_lambda(d, alpha, -w.z));
  };
  const auto over_s = [&](double phi) {
    const auto integrand = [&](double s) {
      if (!valid(s, phi)) return 0.0;
      const Vec3 h = half(s, phi);
      const double ih = dot(wi, h);
      const double t = std::tan(kPi * s / 2);
      const double dtheta = alpha * (kPi / 2) * (1 + t * t) / (1 + alpha * alpha * t * t);
      return masking(h, ih) * ndf(d, alpha, h.z) * ih / mu * std::sin(std::atan(alpha * t)) * dtheta;
    };
    return integrate_where([&](double s) { return valid(s, phi); }, integrand, 1 - 1e-12);
  };
  // The azimuth by a fixed rule (16 panels of 20 Gauss points): where a part's edge appears the
  // integrand has a kink in φ, which an adaptive rule chases at great cost for digits not needed.
  double total = 0;
  for (int panel = 0; panel < 16; ++panel)
    total += boost::math::quadrature::gauss<double, 20>::integrate(over_s, kPi * panel / 16, kPi * (panel + 1) / 16);
  return 2 * total;
}

// --- the net ------------------------------------------------------------------------------------

TEST(SobolNet, EveryDimensionStratifiesEachPowerOfTwoPrefix) {
  constexpr detail::SobolNet net;
  for (int d = 0; d < detail::kSobolDimensions; ++d)
    for (int bits : {1, 4, 10}) {
      const std::uint32_t n = 1u << bits;
      std::vector<int> cells(n, 0);
      for (std::uint32_t i = 0; i < n; ++i) ++cells[std::size_t(net.at(i, d, 0x9e3779b9u) * n)];
      for (std::uint32_t c = 0; c < n; ++c) ASSERT_EQ(cells[c], 1) << "dimension " << d << ", 2^" << bits;
    }
}

TEST(SobolNet, PairsOfDimensionsStratifyElementaryIntervals) {
  // Every 2-D projection of the first 2^10 points puts 4 points into each of the 16 × 16 squares
  // (a (t, 10, 2)-net with t ≤ 2), which independent points do not (the control).
  constexpr detail::SobolNet net;
  constexpr std::uint32_t n = 1024;
  const auto worst = [&](auto&& point) {
    int most = 0;
    std::vector<int> cells(256, 0);
    for (std::uint32_t i = 0; i < n; ++i) {
      const auto [x, y] = point(i);
      most = std::max(most, ++cells[std::size_t(x * 16) * 16 + std::size_t(y * 16)]);
    }
    return most;
  };
  for (int a = 0; a < detail::kSobolDimensions; ++a)
    for (int b = a + 1; b < detail::kSobolDimensions; ++b)
      EXPECT_EQ(worst([&](std::uint32_t i) { return std::pair{net.at(i, a, 12345u), net.at(i, b, 777u)}; }), 4)
          << a << "," << b;
  sampling::SplitMixStream rng(3);
  EXPECT_GT(worst([&](std::uint32_t) { return std::pair{rng.uniform(), rng.uniform()}; }), 4);
}

// --- identity 1: F = 1 reflects everything ------------------------------------------------------

TEST(Walk, WithoutFresnelEverythingIsReflectedAtEveryRoughnessAndAngle) {
  for (Distribution d : {Distribution::ggx, Distribution::beckmann})
    for (double alpha : {0.05, 0.3, 1.0, 2.0})
      for (double mu : {0.1, 0.5, 1.0}) {
        const Albedo a = conductor_albedo({d, alpha}, {&kOne, 1}, mu, paths(kMinPaths))[0];
        EXPECT_NEAR(a.total.value, 1, 3 * a.total.error + kRounding) << int(d) << " alpha " << alpha << " mu " << mu;
        EXPECT_LT(a.total.error, 1e-3);
      }
}

TEST(Walk, RouletteThatForgetsItsWeightsLosesEnergy) {
  Options options = paths(kMinPaths);
  options.faults.roulette_unweighted = true;
  const Albedo a = conductor_albedo({Distribution::ggx, 1.0}, {&kOne, 1}, 0.5, options)[0];
  EXPECT_LT(a.total.value, 1 - 10 * a.total.error);
}

// --- identity 2: the first bounce is the single-scattering model ---------------------------------

TEST(Walk, FirstBounceIsTheSingleScatteringAlbedo) {
  const std::vector<Channel> channels{kOne, kSchlick004};
  for (Distribution d : {Distribution::ggx, Distribution::beckmann})
    for (double alpha : {0.05, 0.3, 1.0})
      for (double mu : {0.1, 0.5, 1.0}) {
        const auto a = conductor_albedo({d, alpha}, channels, mu, paths(2 * kMinPaths));
        for (std::size_t c = 0; c < channels.size(); ++c) {
          const double expected = single_scattering(d, alpha, mu, channels[c]);
          EXPECT_NEAR(a[c].order[0].value, expected, 3 * a[c].order[0].error + kRounding)
              << int(d) << " alpha " << alpha << " mu " << mu << " channel " << c;
        }
      }
}

TEST(Walk, TheQuadratureAgreesWithSpeculasCubatureForGgx) {
  // The reference of the test above, against a second method: the ggx model's albedo (its F0 = 1
  // and 0.04 are Schlick's), at the cubature's 8 digits.
  for (double alpha : {0.05, 0.3, 1.0})
    for (double f0 : {1.0, 0.04})
      for (double mu : {0.1, 0.5, 1.0}) {
        const Model ggx = make_model("ggx", {{"alpha", alpha}, {"f0", f0}});
        const Channel f{Kind::schlick, f0, 1, 5};
        EXPECT_NEAR(single_scattering(Distribution::ggx, alpha, mu, f), analysis::albedo(ggx, std::acos(mu)).value,
                    1e-7)
            << alpha << " " << f0 << " " << mu;
      }
}

TEST(Walk, TheQuadratureAgreesWithSpeculasCubatureForEveryFresnelModel) {
  // The same for the models whose Fresnel is another kind, and for Beckmann-Smith, whose first
  // bounce the walk's Beckmann microsurface is.
  struct Case {
    std::string id;
    ParamValues params;
    Distribution distribution;
    Channel channel;
  };
  const Case cases[] = {
      {"ggx-conductor", {{"alpha", 0.3}, {"eta", 0.2}, {"kappa", 3.1}}, Distribution::ggx,
       Channel{.kind = Kind::conductor, .eta = 0.2, .kappa = 3.1}},
      {"ggx-dielectric", {{"alpha", 0.6}, {"eta", 1.5}}, Distribution::ggx, Channel{.kind = Kind::dielectric, .eta = 1.5}},
      {"ggx-f82", {{"alpha", 0.6}, {"f0", 0.8}, {"tint", 0.5}}, Distribution::ggx,
       Channel{.kind = Kind::f82_tint, .f0 = 0.8, .tint = 0.5}},
      {"beckmann", {{"alpha", 0.05}, {"f0", 1}}, Distribution::beckmann, kOne},
      {"beckmann", {{"alpha", 0.5}, {"f0", 0.04}}, Distribution::beckmann, kSchlick004},
      {"beckmann-conductor", {{"alpha", 1.0}, {"eta", 1.5}, {"kappa", 0.5}}, Distribution::beckmann,
       Channel{.kind = Kind::conductor, .eta = 1.5, .kappa = 0.5}},
  };
  for (const Case& c : cases)
    for (double mu : {0.1, 0.5, 1.0})
      EXPECT_NEAR(single_scattering(c.distribution, c.params.at("alpha"), mu, c.channel),
                  analysis::albedo(make_model(c.id, c.params), std::acos(mu)).value, 1e-7)
          << c.id << " " << c.params.at("alpha") << " " << mu;
}

TEST(Walk, AWrongMaskingFunctionMissesTheSingleScatteringAlbedo) {
  Options options = paths(2 * kMinPaths);
  options.faults.masking_alpha_scale = 1.25;
  const Albedo a = conductor_albedo({Distribution::ggx, 1.0}, {&kOne, 1}, 0.5, options)[0];
  const double expected = single_scattering(Distribution::ggx, 1.0, 0.5, kOne);
  EXPECT_GT(std::abs(a.order[0].value - expected), 10 * a.order[0].error);
}

// --- identity 3: reciprocity --------------------------------------------------------------------

// z-scores of f_ms(a, b) − f_ms(b, a) per channel (f_ms·μ_o is what the walk estimates).
std::vector<double> reciprocity_z(Distribution d, double alpha, const Vec3& a, const Vec3& b, const Options& options) {
  const std::vector<Channel> channels{kOne, kSchlick004, Channel{Kind::conductor, 1, 1, 5, 1, 1.5, 0.5}};
  const auto ab = conductor_brdf_cos({d, alpha}, channels, a, b, options);
  const auto ba = conductor_brdf_cos({d, alpha}, channels, b, a, options);
  std::vector<double> z;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const double f1 = ab[c].multiple.value / b.z, e1 = ab[c].multiple.error / b.z;
    const double f2 = ba[c].multiple.value / a.z, e2 = ba[c].multiple.error / a.z;
    EXPECT_GT(f1, 0);
    z.push_back((f1 - f2) / std::hypot(e1, e2));
  }
  return z;
}

TEST(Walk, MultipleScatteringIsReciprocal) {
  for (Distribution d : {Distribution::ggx, Distribution::beckmann})
    for (const auto& [a, b] : {std::pair{direction(0.2, 0), direction(0.9, 2)}, std::pair{direction(0.5, 0), direction(0.35, 3)}})
      for (double z : reciprocity_z(d, 0.6, a, b, paths(2 * kMinPaths))) EXPECT_LT(std::abs(z), 3) << int(d);
}

TEST(Walk, DroppingTheSecondBouncesFresnelBreaksReciprocity) {
  Options options = paths(2 * kMinPaths);
  options.faults.drop_fresnel_at_bounce = 2;
  const auto z = reciprocity_z(Distribution::ggx, 0.6, direction(0.2, 0), direction(0.9, 2), options);
  EXPECT_LT(std::abs(z[0]), 3);   // F = 1 has no Fresnel to drop
  EXPECT_GT(std::abs(z[1]), 10);  // Schlick, F0 = 0.04
  EXPECT_GT(std::abs(z[2]), 10);  // a conductor
}

// --- identity 4: a constant F scales order k by F^k ----------------------------------------------

std::vector<Albedo> with_constant_fresnel(const Options& options) {
  const std::vector<Channel> channels{kOne, Channel{Kind::schlick, 0.7, 0.7, 5}};
  return conductor_albedo({Distribution::ggx, 1.5}, channels, 0.4, options);
}

TEST(Walk, AConstantFresnelScalesEachOrderByItsPower) {
  const auto a = with_constant_fresnel(paths(kMinPaths));
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(a[1].order[k].value, std::pow(0.7, k + 1) * a[0].order[k].value, 1e-12) << "order " << k + 1;
  EXPECT_LT(a[1].order[3].value, std::pow(0.7, 4) * a[0].order[3].value);
  Options faulty = paths(kMinPaths);
  faulty.faults.drop_fresnel_at_bounce = 2;
  const auto b = with_constant_fresnel(faulty);
  EXPECT_GT(std::abs(b[1].order[1].value - 0.49 * b[0].order[1].value), 1e-3);
}

// --- a rough dielectric: both sides, energy conserved, first bounces ---------------------------

TEST(DielectricWalk, ReflectionAndTransmissionSumToOne) {
  for (Distribution d : {Distribution::ggx, Distribution::beckmann})
    for (double eta : {1.5, 1 / 1.5})
      for (double alpha : {0.05, 0.5, 1.5})
        for (double mu : {0.2, 0.7, 1.0}) {
          const DielectricAlbedo a = dielectric_albedo({d, alpha}, eta, mu, paths(kMinPaths));
          EXPECT_NEAR(a.energy.total.value, 1, 3 * a.energy.total.error + kRounding)
              << int(d) << " eta " << eta << " alpha " << alpha << " mu " << mu;
          EXPECT_NEAR(a.energy.total.value, a.reflection.total.value + a.transmission.total.value, kRounding);
        }
  Options faulty = paths(kMinPaths);
  faulty.faults.roulette_unweighted = true;
  const DielectricAlbedo lossy = dielectric_albedo({Distribution::ggx, 1.5}, 1 / 1.5, 0.7, faulty);
  EXPECT_LT(lossy.energy.total.value, 1 - 10 * lossy.energy.total.error);
}

TEST(DielectricWalk, FirstBounceIsTheSingleScatteringReflectionAndTransmission) {
  for (Distribution d : {Distribution::ggx, Distribution::beckmann})
    for (double eta : {1.5, 1 / 1.5})
      for (double alpha : {0.1, 0.6})
        for (double mu : {0.3, 0.9}) {
          const DielectricAlbedo a = dielectric_albedo({d, alpha}, eta, mu, paths(2 * kMinPaths));
          const Channel f{Kind::dielectric, 1, 1, 5, 1, eta};
          const std::string where = fmt::format("{} eta {} alpha {} mu {}", int(d), eta, alpha, mu);
          EXPECT_NEAR(a.reflection.order[0].value, single_scattering(d, alpha, mu, f, Side::reflection),
                      3 * a.reflection.order[0].error + kRounding) << where;
          EXPECT_NEAR(a.transmission.order[0].value, single_scattering(d, alpha, mu, f, Side::transmission),
                      3 * a.transmission.order[0].error + 1e-6) << where;
        }
  Options faulty = paths(2 * kMinPaths);
  faulty.faults.masking_alpha_scale = 1.25;
  const DielectricAlbedo wrong = dielectric_albedo({Distribution::ggx, 0.6}, 1.5, 0.3, faulty);
  const double expected = single_scattering(Distribution::ggx, 0.6, 0.3, Channel{Kind::dielectric, 1, 1, 5, 1, 1.5},
                                            Side::transmission);
  EXPECT_GT(std::abs(wrong.transmission.order[0].value - expected), 10 * wrong.transmission.order[0].error);
}

// --- what a user sees: determinism, errors, progress, stops -------------------------------------

TEST(Walk, SameSeedSameResultWhateverTheThreadCount) {
  const auto run = [] {
    return conductor_albedo({Distribution::ggx, 0.7}, {&kSchlick004, 1}, 0.3, paths(kMinPaths, 11))[0];
  };
  const Albedo many = run();
  Albedo one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = run();
  }
  for (int k = 0; k < kOrders; ++k) EXPECT_EQ(one.order[k].value, many.order[k].value);
  EXPECT_EQ(one.multiple.error, many.multiple.error);
  const Albedo other = conductor_albedo({Distribution::ggx, 0.7}, {&kSchlick004, 1}, 0.3, paths(kMinPaths, 12))[0];
  EXPECT_NE(other.total.value, many.total.value);
  EXPECT_NEAR(other.total.value, many.total.value, 5 * std::hypot(other.total.error, many.total.error));
}

TEST(Walk, RefusesValuesOutsideItsDomainWithTheReason) {
  const auto error = [](Microsurface s, Channel f, double mu, std::uint64_t n) {
    try {
      conductor_albedo(s, {&f, 1}, mu, paths(n));
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const Microsurface ok{Distribution::ggx, 0.5};
  EXPECT_NE(error({Distribution::ggx, 0}, kOne, 0.5, kMinPaths).find("alpha"), std::string::npos);
  EXPECT_NE(error({Distribution::ggx, NAN}, kOne, 0.5, kMinPaths).find("alpha"), std::string::npos);
  EXPECT_NE(error(ok, kOne, 0, kMinPaths).find("mu"), std::string::npos);
  EXPECT_NE(error(ok, kOne, 1.5, kMinPaths).find("mu"), std::string::npos);
  EXPECT_NE(error(ok, Channel{Kind::schlick, 1.5}, 0.5, kMinPaths), "");
  EXPECT_NE(error(ok, Channel{Kind::dielectric, 1, 1, 5, 1, 0}, 0.5, kMinPaths), "");
  EXPECT_NE(error(ok, Channel{Kind::dielectric, 1, 1, 5, 1, NAN}, 0.5, kMinPaths), "");
  EXPECT_NE(error(ok, Channel{Kind::conductor, 1, 1, 5, 1, 0.2, -1}, 0.5, kMinPaths), "");
  EXPECT_NE(error(ok, kOne, 0.5, kMaxPaths + 1).find("paths"), std::string::npos);
  EXPECT_NE(error(ok, kOne, 0.5, kMinPaths - 1).find("paths"), std::string::npos);
  EXPECT_THROW(conductor_albedo(ok, {}, 0.5, paths(kMinPaths)), InvalidArgument);
  EXPECT_THROW(conductor_brdf_cos(ok, {&kOne, 1}, direction(0.5, 0), Vec3{0, 0, -1}, paths(kMinPaths)), InvalidArgument);
}

TEST(Walk, ReportsProgressAndStopsWhenAsked) {
  Options options = paths(200 * kBlockPaths);
  std::vector<double> seen;
  options.progress = [&](double done) { seen.push_back(done); };
  conductor_albedo({Distribution::ggx, 0.5}, {&kOne, 1}, 0.5, options);
  ASSERT_GE(seen.size(), 3u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 1.0);

  options.progress = [](double done) {
    if (done > 0) request_stop(2);
  };
  EXPECT_THROW(conductor_albedo({Distribution::ggx, 0.5}, {&kOne, 1}, 0.5, options), Interrupted);
  clear_stop_request();
}

}  // namespace
}  // namespace specula::walk
