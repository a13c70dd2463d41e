// User-defined models: model files and inline definitions give the built-in models' numbers, the
// numerical support/half-maximum/kinks of a formula lobe are where the closed forms put them, and
// every kind of bad input is one line naming FILE:LINE (and the column where there is one).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "specula/analysis/albedo.h"
#include "specula/brdf/directions.h"
#include "error_message.h"
#include "specula/exceptions.h"
#include "specula/io/files.h"
#include "specula/catalogue/model_file.h"
#include "specula/lobes/closed_form.h"
#include "specula/simd/brdf.h"

namespace specula {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

using testing::error_of;

/// The user-written copies of the built-in families (examples/models/builtin-copies.toml),
/// registered once for the whole binary.
class CopiesEnvironment : public ::testing::Environment {
 public:
  void SetUp() override { register_model_file(SPECULA_SOURCE_DIR "/examples/models/builtin-copies.toml"); }
};
const auto* const kCopies = ::testing::AddGlobalTestEnvironment(new CopiesEnvironment);

double relative(double a, double b) { return a == b ? 0 : std::abs(a - b) / std::max(std::abs(a), std::abs(b)); }

TEST(ModelFile, CopiesOfTheLobeFamiliesEvaluateAsTheBuiltIns) {
  const std::pair<const char*, const char*> pairs[] = {{"my-phong", "phong"}, {"my-schlick", "schlick"},
                                                       {"my-schlick-modified", "schlick-modified"},
                                                       {"my-gauss", "gauss"}, {"my-log", "log"}};
  for (const auto& [mine, builtin] : pairs)
    for (const double n : {0.01, 1.0, 20.0, 1000.0, 1e6}) {
      const Model a = make_model(mine, {{"n", n}}).with_coef(1), b = make_model(builtin, {{"n", n}});
      for (double c = 0; c <= 1; c += 1.0 / 512) {
        EXPECT_LE(relative(lobes::eval(a.lobe(), c), lobes::eval(b.lobe(), c)), 1e-12)
            << mine << " n=" << n << " c=" << c;
      }
      for (const double u : {1e-15, 1e-9, 1e-6, 1e-3, 0.1, 1.0, 10.0})
        EXPECT_LE(relative(lobes::at_log_cos(a.lobe(), u), lobes::at_log_cos(b.lobe(), u)), 1e-12)
            << mine << " n=" << n << " u=" << u;
    }
}

TEST(ModelFile, QuadratureAndFormulaNormalizationsMatchTheClosedForms) {
  for (const double n : {1e-3, 0.5, 1.0, 20.0, 1000.0, 1e6, 1e9}) {
    EXPECT_LE(relative(make_model("my-log", {{"n", n}}).coef(), lobes::log_rv(n)), 1e-12) << n;
    EXPECT_LE(relative(make_model("my-phong", {{"n", n}}).coef(), lobes::phong_rv(n)), 1e-15) << n;
    EXPECT_LE(relative(make_model("my-blinn-phong", {{"n", n}}).coef(), lobes::blinn_phong_nh(n)), 1e-12) << n;
    EXPECT_LE(relative(make_model("my-schlick", {{"n", n}}).coef(), lobes::schlick_rv(n)), 1e-12) << n;
  }
}

TEST(ModelFile, CopiesOfTheFullBrdfsEvaluateAsTheBuiltIns) {
  const std::pair<const char*, const char*> pairs[] = {
      {"my-ggx", "ggx"}, {"my-cook-torrance", "cook-torrance"}, {"my-ward", "ward"}, {"my-lambert", "lambert"}};
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> theta(0, 1.5), phi(0, 2 * std::numbers::pi);
  const Vec3 n{0, 0, 1};
  for (const auto& [mine, builtin] : pairs) {
    const Model a = make_model(mine), b = make_model(builtin);
    for (int i = 0; i < 2000; ++i) {
      const Vec3 l = from_spherical(theta(rng), phi(rng)), v = from_spherical(theta(rng), phi(rng));
      EXPECT_LE(relative(a(n, l, v), b(n, l, v)), 1e-12) << mine;
    }
  }
}

TEST(ModelFile, AlbedoOfCopiesMatchesTheBuiltIns) {
  const std::pair<const char*, const char*> pairs[] = {{"my-log", "log-normalized"}, {"my-ggx", "ggx"},
                                                       {"my-cook-torrance", "cook-torrance"}, {"my-ward", "ward"}};
  for (const auto& [mine, builtin] : pairs)
    for (const double theta : {0.0, 0.5, 1.2}) {
      const double a = analysis::albedo(make_model(mine), theta).value;
      const double b = analysis::albedo(make_model(builtin), theta).value;
      EXPECT_LE(std::abs(a - b), 1e-9) << mine << " theta=" << theta;
    }
}

TEST(FormulaLobe, FindsSupportHalfMaximumAndKinks) {
  // F = max(0, 1 − n(1 − c)/4)⁴: support end 1 − c = 4/n, half-maximum 1 − c = 4(1 − 2^(−1/4))/n.
  const double n = 50;
  const Model m = make_model("lobe: max(0, 1 - n*(1-c)/4)^4", {{"n", n}});
  const auto& lobe = std::get<lobes::Formula>(m.lobe());
  EXPECT_LE(relative(lobe.support_log_cos(), -std::log1p(-4 / n)), 1e-14);
  EXPECT_LE(relative(lobe.half_max_log_cos(), -std::log1p(-4 * (1 - std::pow(2.0, -0.25)) / n)), 1e-14);
  // min(1, 2cⁿ) bends where 2cⁿ = 1: u = ln 2 / n.
  const Model kinked = make_model("lobe: min(1, 2*c^n)", {{"n", n}});
  const auto kinks = std::get<lobes::Formula>(kinked.lobe()).kinks_log_cos();
  ASSERT_EQ(kinks.size(), 1u);
  EXPECT_LE(relative(kinks[0], std::numbers::ln2 / n), 1e-14);
  // Its support ends only where 2cⁿ underflows (u ≈ 745/n): F is 0 in double beyond.
  const double support = std::get<lobes::Formula>(kinked.lobe()).support_log_cos();
  EXPECT_GT(support, 700 / n);
  EXPECT_EQ(kinked.lobe().index(), 5u);
  EXPECT_EQ(lobes::at_log_cos(kinked.lobe(), support * 1.01), 0.0);
  EXPECT_GT(lobes::at_log_cos(kinked.lobe(), support * 0.99), 0.0);
}

TEST(FormulaLobe, AnInlineLobeIsTheBuiltInOne) {
  const Model inline_phong = make_model("lobe: c^n", {{"n", 20}});
  EXPECT_EQ(inline_phong.id(), "lobe: c^n");
  EXPECT_EQ(inline_phong.param("n"), 20);
  for (const double c : {0.0, 0.3, 0.9, 1.0}) EXPECT_EQ(inline_phong.at_cos(c), std::pow(c, 20.0));
  EXPECT_EQ(inline_phong.at_cos(-0.5), 0.0);
  EXPECT_EQ(make_model("lobe: c^n").param("n"), 1);  // not given: 1
  const Model brdf = make_model("brdf: rho/pi", {{"rho", 0.5}});
  EXPECT_FALSE(brdf.is_lobe());
  EXPECT_DOUBLE_EQ(brdf(Vec3{0, 0, 1}, Vec3{0, 0, 1}, Vec3{0, 0, 1}), 0.5 / std::numbers::pi);
  // The column in the definition; the interface that asked names its field before it (queries).
  EXPECT_THAT(error_of([] { (void)make_model("lobe: c^^n"); }), StartsWith("column 9: "));
  EXPECT_EQ(error_of([] { (void)make_model("lobe: foo(c)"); }), "column 7: unknown function 'foo'");
}

// The scalar batch (lobes::Formula::eval_batch, the analysis's path) is bit-identical to the
// scalar lobe; the vectorized path (simd/formula.h) is within the bound simd/lobes.h states.
TEST(FormulaLobe, TheBatchPathsMatchTheScalarOnes) {
  const Model lobe = make_model("my-log", {{"n", 300}});
  const auto& formula = std::get<lobes::Formula>(lobe.lobe());
  std::vector<double> c(1000), scalar_batch(c.size()), batch(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = -0.01 + 1.02 * double(i) / double(c.size() - 1);
  formula.eval_batch(c, scalar_batch);
  simd::eval_batch(simd::spec_of(lobe.lobe()), simd::Tier::exact, std::span<const double>(c), std::span<double>(batch));
  const auto exact = simd::error_bound<double>(simd::Family::formula, simd::Tier::exact);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double f = lobes::eval(lobe.lobe(), c[i]);
    EXPECT_EQ(scalar_batch[i], f) << c[i];
    EXPECT_LE(std::abs(batch[i] - f), exact.allowed(f, f > 0 ? std::log(f) : 0)) << c[i];
  }
  std::vector<float> cf(c.begin(), c.end()), batch_f(c.size());
  simd::eval_batch(simd::spec_of(lobe.lobe()), simd::Tier::fast, std::span<const float>(cf), std::span<float>(batch_f));
  const auto fast = simd::error_bound<float>(simd::Family::formula, simd::Tier::fast);
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double f = lobes::eval(lobe.lobe(), double(cf[i]));
    EXPECT_LE(std::abs(double(batch_f[i]) - f), fast.allowed(f, f > 0 ? std::log(f) : 0)) << cf[i];
  }

  // A formula BRDF through simd::eval_batch: its dot products and program, as the scalar model
  // within the formula's double bound (here F is not ≤ 1: relative to f).
  const Model ggx = make_model("my-cook-torrance", {{"m", 0.2}});
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> theta(0, 1.6), phi(0, 2 * std::numbers::pi);
  constexpr std::size_t kCount = 700;
  std::vector<double> d[9];
  for (auto& column : d) column.resize(kCount);
  for (std::size_t i = 0; i < kCount; ++i) {
    const Vec3 l = from_spherical(theta(rng), phi(rng)), v = from_spherical(theta(rng), phi(rng));
    d[0][i] = 0, d[1][i] = 0, d[2][i] = 1, d[3][i] = l.x, d[4][i] = l.y, d[5][i] = l.z, d[6][i] = v.x, d[7][i] = v.y,
    d[8][i] = v.z;
  }
  std::vector<double> f(kCount);
  simd::eval_batch(ggx, simd::Tier::exact, {d[0], d[1], d[2], d[3], d[4], d[5], d[6], d[7], d[8]}, f);
  for (std::size_t i = 0; i < kCount; ++i) {
    const double expected = ggx(Vec3{0, 0, 1}, Vec3{d[3][i], d[4][i], d[5][i]}, Vec3{d[6][i], d[7][i], d[8][i]});
    EXPECT_LE(std::abs(f[i] - expected), 64 * 0x1p-52 * std::abs(expected)) << i;
  }
}

// ---- bad input --------------------------------------------------------------------------------

constexpr const char* kGood = R"([[model]]
id = "x"
name = "x"
kind = "lobe"
form = "rv"
lobe = "c^n"
normalization = "none"
[model.params.n]
default = 2
min = 0
max = 10
)";

std::string with(std::string_view from, std::string_view to) {
  std::string text = kGood;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  return text;
}

std::string parse_error(const std::string& text) {
  return error_of([&] { (void)parse_model_file(text, "m.toml"); });
}

TEST(ModelFileErrors, TheControlParses) {
  const auto models = parse_model_file(kGood, "m.toml");
  ASSERT_EQ(models.size(), 1u);
  EXPECT_EQ(models[0].origin.kind, OriginKind::file);
  EXPECT_EQ(to_string(models[0].origin), "m.toml:1");
  EXPECT_EQ(make_model(std::make_shared<const ModelInfo>(models[0])).at_cos(0.5), 0.25);
}

TEST(ModelFileErrors, SyntaxErrorsNameLineAndColumn) {
  EXPECT_EQ(parse_error(with("lobe = \"c^n\"", "lobe = \"c^*n\"")), "m.toml:6: column 11: lobe: expected a number, a variable, a function call or '(' but found '*'");
  EXPECT_THAT(parse_error(with("lobe = \"c^n\"", "lobe = \"c^n")), StartsWith("m.toml:6: column "));
  EXPECT_THAT(parse_error(with("lobe = \"c^n\"", "lobe = \"c^k\"")), StartsWith("m.toml:6: column 11: lobe: unknown variable 'k'"));
}

TEST(ModelFileErrors, EveryStructuralMistakeIsOneLine) {
  const std::pair<std::string, std::string> cases[] = {
      {with("id = \"x\"", "id = \"phong\""), "m.toml:1: model id 'phong' is already taken"},  // by register
      {with("min = 0\n", ""), "m.toml:8: parameter 'n' lacks key 'min' (every parameter has a range)"},
      {with("default = 2", "default = 20"), "m.toml:9: parameter 'n': default 20 is outside its range [0, 10]"},
      {with("name = \"x\"\n", ""), "m.toml:1: missing key 'name'"},
      {with("form = \"rv\"", "from = \"rv\""), "m.toml:5: unknown key 'from' in a model"},
      {with("max = 10", "max = 10\nmeening = 1"), "m.toml:12: unknown key 'meening' in parameter 'n'"},
      {with("kind = \"lobe\"", "kind = \"lobes\""), "m.toml:4: kind 'lobes' is neither"},
      {with("form = \"rv\"", "form = \"rr\""), "m.toml:5: unknown form 'rr'"},
      {with("form = \"rv\"\n", ""), "m.toml:1: missing key 'form'"},
      {with("lobe = \"c^n\"", "lobe = \"" + std::string(5000, 'c') + "\""), "m.toml:6: key 'lobe' is too long"},
      {with("lobe = \"c^n\"", "lobe = \"" + std::string(100, '(') + "c" + std::string(100, ')') + "\""), "no error"},
      {with("lobe = \"c^n\"", "lobe = \"" + [] { std::string s = "c"; for (int i = 0; i < 80; ++i) s = "c^(" + s + ")"; return s; }() + "\""),
       "m.toml:6: lobe: formula nests too deep"},
      {with("[model.params.n]", "[model.params.pi]"), "m.toml:8: parameter name 'pi' is reserved"},
      {with("[model.params.n]", "[model.params.a__b]"), "m.toml:8: parameter name 'a__b' may not start with _ or contain __"},
      {with("[model.params.n]", "[model.params._b]"), "m.toml:8: parameter name '_b' may not start with _"},
      {with("lobe = \"c^n\"", "lobe_u = \"exp(-n*u)\"") + "[model.params.u]\ndefault = 1\nmin = 0\nmax = 2\n",
       "m.toml:8: parameter name 'u' is used twice (or is an input)"},  // a fuzz finding
      {with("[model.params.n]", "[model.params.a_b]"), "m.toml:6: column 11: lobe: unknown variable 'n'"},  // control
      {with("lobe = \"c^n\"", "brdf = \"nl\""), "m.toml:6: key 'brdf' belongs to kind = \"brdf\""},
  };
  for (const auto& [text, expected] : cases) {
    const std::string got = error_of([&] { register_models(parse_model_file(text, "m.toml")); });
    EXPECT_THAT(got, StartsWith(expected)) << text;
    EXPECT_EQ(got.find('\n'), std::string::npos);
  }
  clear_registered_models();
  register_model_file(SPECULA_SOURCE_DIR "/examples/models/builtin-copies.toml");
}

TEST(ModelFileErrors, DuplicateIdsInOneFile) {
  const std::string twice = std::string(kGood) + "\n" + kGood;
  EXPECT_THAT(error_of([&] { register_models(parse_model_file(twice, "m.toml")); }),
              StartsWith("m.toml:13: model id 'x' is defined twice (first at m.toml:1)"));
  EXPECT_EQ(find_model("x"), nullptr);
}

TEST(ModelFileErrors, ANegativeOrNanLobeIsNoInputError) {
  EXPECT_EQ(parse_error(with("lobe = \"c^n\"", "lobe = \"c - 2\"")), "no error");
  EXPECT_EQ(parse_error(with("lobe = \"c^n\"", "lobe = \"log(c - 2)\"")), "no error");
}

}  // namespace
}  // namespace specula
