// The vectorized formula path (simd/formula.h) on every instruction set this CPU runs: each op
// against std:: within the ULP simd/formula.h states for its lane type, with libm's special
// values; the user-written copies of the built-in lobes (examples/models/builtin-copies.toml)
// within error_bound<T>(Family::formula, tier) of simd/lobes.h against the scalar Formula; the
// formula BRDFs through simd::eval_batch; and negative controls that show the checks can fail.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "simd/probe_cosines.h"
#include "simd/target_label.h"
#include "specula/catalogue/model_file.h"
#include "specula/simd/formula.h"
#include "specula/simd/lobes.h"
#include "specula/simd/targets.h"

namespace specula::simd {
namespace {

// ---- per op ----------------------------------------------------------------------------------

struct OpCase {
  const char* formula;  ///< in x, or x and y
  double (*reference)(double, double);
  double ulp_double, ulp_float;
  double per_ln_float = 0;  ///< float pow: its rounding grows with |ln result| (ε per unit)
};

const OpCase kOps[] = {
    {"log(x)", [](double x, double) { return std::log(x); }, 1, 1},
    {"log2(x)", [](double x, double) { return std::log2(x); }, 2, 2},
    {"exp(x)", [](double x, double) { return std::exp(x); }, 1, 1},
    {"expm1(x)", [](double x, double) { return std::expm1(x); }, 3, 2},
    {"log1p(x)", [](double x, double) { return std::log1p(x); }, 2, 2},
    {"sin(x)", [](double x, double) { return std::sin(x); }, 2, 2},
    {"cos(x)", [](double x, double) { return std::cos(x); }, 2, 2},
    {"acos(x)", [](double x, double) { return std::acos(x); }, 2, 2},
    {"asin(x)", [](double x, double) { return std::asin(x); }, 2, 2},
    {"sqrt(x)", [](double x, double) { return std::sqrt(x); }, 0, 0},
    {"abs(x)", [](double x, double) { return std::abs(x); }, 0, 0},
    {"-x", [](double x, double) { return -x; }, 0, 0},
    {"x + y", [](double x, double y) { return x + y; }, 0, 0},
    {"x - y", [](double x, double y) { return x - y; }, 0, 0},
    {"x * y", [](double x, double y) { return x * y; }, 0, 0},
    {"x / y", [](double x, double y) { return x / y; }, 0, 0},
    {"min(x, y)", [](double x, double y) { return y < x ? y : x; }, 0, 0},
    {"max(x, y)", [](double x, double y) { return x < y ? y : x; }, 0, 0},
    {"pow(x, y)", [](double x, double y) { return std::pow(x, y); }, 2, 3, 1.2},
    // x·x is the square correctly rounded; libm's pow(x, 2) is not (1 ulp off at x = 0.70608656112964996):
    // it passed only where the compiler turned the call into x·x.
    {"x^2", [](double x, double) { return x * x; }, 0, 0},
    {"x^3", [](double x, double) { return std::pow(x, 3); }, 2, 2},
    {"x^4", [](double x, double) { return std::pow(x, 4); }, 3, 3},
    {"x^-3", [](double x, double) { return std::pow(x, -3); }, 3, 3},
    {"x^20", [](double x, double) { return std::pow(x, 20); }, 2, 19, 0},
};

/// Values over the whole range, both signs, around 0 and 1 and ±π, and the special values.
std::vector<double> op_inputs(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<double> x;
  for (std::size_t i = 0; i < count; ++i) {
    const double sign = i % 2 ? -1 : 1;
    switch (i % 5) {
      case 0: x.push_back(sign * std::pow(10.0, -310 + 620 * uniform(rng))); break;
      case 1: x.push_back(sign * 2 * uniform(rng)); break;
      case 2: x.push_back(sign * 60 * uniform(rng)); break;
      case 3: x.push_back(sign * std::pow(10.0, -12 * uniform(rng))); break;
      default: x.push_back(sign * (800 * uniform(rng))); break;
    }
  }
  for (const double v : {0.0, -0.0, 1.0, -1.0, 2.0, -2.0, 0.5, -0.5, 3.0, 3.14159265358979, 1e-320, -1e-320,
                         709.0, 709.78, 710.0, -745.0, -1000.0, 88.7, 89.0, -104.0, 1e5, -1e5, 1e300})
    x.push_back(v);
  for (const double v : {INFINITY, -INFINITY, NAN}) x.push_back(v);
  return x;
}

/// Whether `got` is within `ulp` (relative, ε of T) of `ref`, with libm's special values exactly.
template <class T>
bool within(double got, double exact, double ulp, double per_ln) {
  const double ref = double(T(exact));  // libm's double result rounded to the lane type
  if (std::isnan(ref) || std::isnan(got)) return std::isnan(ref) && std::isnan(got);
  if (!std::isfinite(ref) || ref == 0) return got == ref && std::signbit(got) == std::signbit(ref);
  constexpr double eps = std::numeric_limits<T>::epsilon(), tiny = std::numeric_limits<T>::min();
  if (std::abs(ref) < tiny) return std::abs(got - ref) <= (ulp + 1) * eps * tiny;  // subnormal results
  if (std::abs(ref) > std::numeric_limits<T>::max()) return std::isinf(got);  // overflows in T
  return std::abs(got - ref) <= (ulp + per_ln * std::abs(std::log(std::abs(ref)))) * eps * std::abs(ref);
}

template <class T>
std::vector<T> lane_values(const std::vector<double>& v) {
  return std::vector<T>(v.begin(), v.end());
}

/// Each op of kOps over op_inputs, in double lanes (exact) or float lanes (fast).
template <class T>
void expect_ops_within_bounds() {
  const std::vector<double> xd = op_inputs(20000, 1), yd = op_inputs(20000, 2);
  const std::vector<T> x = lane_values<T>(xd), y = lane_values<T>(yd);
  for (const OpCase& op : kOps) {
    expr::Program program({"x", "y"}, {});
    program.set_result(op.formula);
    std::vector<T> got(x.size());
    const std::span<const T> inputs[] = {x, y};
    if constexpr (sizeof(T) == 8) eval_program(program, inputs, {}, got);
    else eval_program(program, Tier::fast, inputs, {}, got);
    const double ulp = sizeof(T) == 8 ? op.ulp_double : op.ulp_float, per_ln = sizeof(T) == 8 ? 0 : op.per_ln_float;
    std::size_t failures = 0;
    std::string first;
    double max_ulp = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double ref = op.reference(double(x[i]), double(y[i])), rounded = double(T(ref));
      if (std::isnormal(rounded) && std::isfinite(double(got[i])))
        max_ulp = std::max(max_ulp, std::abs(double(got[i]) - rounded) / std::abs(rounded) / std::numeric_limits<T>::epsilon());
      if (within<T>(double(got[i]), ref, ulp, per_ln)) continue;
      if (failures++ == 0)
        first = fmt::format("x = {:.17g}, y = {:.17g}: got {:.17g}, libm {:.17g}", double(x[i]), double(y[i]),
                            double(got[i]), ref);
    }
    EXPECT_EQ(failures, 0u) << current_target().name << " " << op.formula << (sizeof(T) == 8 ? " double" : " float")
                            << ", first " << first << ", max " << max_ulp << " ulp";
  }
}

class EveryTargetFormula : public ::testing::TestWithParam<std::int64_t> {
 protected:
  void SetUp() override { scope_.emplace(GetParam()); }
  void TearDown() override { scope_.reset(); }

 private:
  std::optional<ScopedTarget> scope_;
};

TEST_P(EveryTargetFormula, DoubleLaneOpsWithinStatedUlp) { expect_ops_within_bounds<double>(); }

TEST_P(EveryTargetFormula, FloatLaneOpsWithinStatedUlp) { expect_ops_within_bounds<float>(); }

// ---- the user copies of the built-in lobes -------------------------------------------------

const std::vector<ModelInfo>& builtin_copies() {
  static const std::vector<ModelInfo> infos = load_model_file(SPECULA_SOURCE_DIR "/examples/models/builtin-copies.toml");
  return infos;
}

constexpr double kFormulaExponents[] = {1e-3, 0.1, 1, 5, 20, 100, 1000, 1e4, 1e6, 1e9};

/// The user lobes at exponent n (the copies of schlick-modified at s = 1.25).
std::vector<Model> copies_at(double n) {
  std::vector<Model> out;
  for (const ModelInfo& info : builtin_copies())
    if (info.kind == ModelKind::lobe) out.push_back(make_model(std::make_shared<ModelInfo>(info), {{"n", n}}));
  return out;
}

struct Worst {
  std::size_t failures = 0;
  double ratio = 0;  ///< the largest |F̃ − F| / allowed
  std::string where;
};

/// got against the scalar double Formula at the same (lane-type) cosines, within `bound`.
template <class T>
Worst check_copy(const lobes::Lobe& lobe, const ErrorBound& bound, const std::vector<T>& c, const std::vector<T>& got) {
  Worst w;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double f = lobes::eval(lobe, double(c[i]));
    if (std::isnan(f) || std::isnan(got[i])) {
      w.failures += std::isnan(f) != std::isnan(got[i]);
      continue;
    }
    const double error = std::abs(double(got[i]) - f), allowed = bound.allowed(f, f > 0 ? std::log(f) : 0);
    w.failures += error > allowed;
    const double ratio = allowed > 0 ? error / allowed : (error > 0 ? INFINITY : 0);
    if (ratio > w.ratio) {
      w.ratio = ratio;
      w.where = fmt::format("c = {:.9g}: got {:.17g}, scalar {:.17g}, error {:.3g}, allowed {:.3g}", double(c[i]),
                            double(got[i]), f, error, allowed);
    }
  }
  return w;
}

template <class T>
void expect_copies_within_bounds(std::size_t dense) {
  for (const double n : kFormulaExponents)
    for (const Model& model : copies_at(double(T(n))))
      for (const Tier tier : {Tier::exact, Tier::fast}) {
        const std::vector<T> c = probe_cosines<T>(double(T(n)), dense);
        std::vector<T> got(c.size());
        eval_batch(spec_of(model.lobe()), tier, std::span<const T>(c), std::span<T>(got));
        const Worst w = check_copy(model.lobe(), error_bound<T>(Family::formula, tier), c, got);
        EXPECT_EQ(w.failures, 0u) << current_target().name << " " << model.id() << " " << to_string(tier)
                                  << (sizeof(T) == 8 ? " double" : " float") << " n = " << n << ", worst "
                                  << w.where << " (" << w.ratio << " × allowed)";
      }
}

TEST_P(EveryTargetFormula, FloatCopiesWithinStatedBounds) { expect_copies_within_bounds<float>(1500); }

TEST_P(EveryTargetFormula, DoubleCopiesWithinStatedBounds) { expect_copies_within_bounds<double>(1500); }

INSTANTIATE_TEST_SUITE_P(Simd, EveryTargetFormula, ::testing::ValuesIn(runnable_targets()), target_label);

// ---- negative controls and conventions --------------------------------------------------------

TEST(SimdFormula, TheCopyCheckCatchesAnErrorJustAboveTheBound) {
  const std::vector<float> c{0.999f, 0.99f, 0.97f, 0.95f};
  for (const Model& model : copies_at(20))
    for (const Tier tier : {Tier::exact, Tier::fast}) {
      const ErrorBound bound = error_bound<float>(Family::formula, tier);
      std::vector<float> got(c.size());
      for (std::size_t i = 0; i < c.size(); ++i) {
        const double f = lobes::eval(model.lobe(), double(c[i]));
        got[i] = float(f + 1.5 * bound.allowed(f, std::log(f)) + 2 * std::numeric_limits<float>::epsilon() * f);
      }
      EXPECT_EQ(check_copy(model.lobe(), bound, c, got).failures, c.size()) << model.id() << " " << to_string(tier);
    }
}

TEST(SimdFormula, TheFastTierIsNotWithinTheExactBound) {
  // The float lanes' error is visible: the exact tier's bound would fail them, so the tests of the
  // two tiers measure different paths.
  const Model log_copy = make_model(std::make_shared<ModelInfo>(builtin_copies()[5]), {{"n", 20.0}});
  ASSERT_EQ(log_copy.id(), "my-log");
  const std::vector<float> c = probe_cosines<float>(20, 1500);
  std::vector<float> got(c.size());
  eval_batch(spec_of(log_copy.lobe()), Tier::fast, std::span<const float>(c), std::span<float>(got));
  EXPECT_GT(check_copy(log_copy.lobe(), error_bound<float>(Family::formula, Tier::exact), c, got).failures, 0u);
}

TEST(SimdFormula, OpCheckCatchesAnErrorOfOneUlpMore) {
  const double ref = std::log(3.0);
  EXPECT_TRUE(within<double>(ref * (1 + 2 * 0x1p-52), ref, 2, 0));
  EXPECT_FALSE(within<double>(ref * (1 + 3 * 0x1p-52), ref, 2, 0));
  EXPECT_FALSE(within<float>(NAN, INFINITY, 2, 0));
  EXPECT_FALSE(within<float>(0.0f, -0.0, 2, 0));
}

TEST(SimdFormula, LobeConventionsAndLengths) {
  // c ≤ 0 gives 0, c > 1 counts as 1, NaN stays NaN; any length, the tail included.
  const std::vector<Model> copies = copies_at(20);
  const Model& model = copies[5];
  for (const std::size_t length : {0, 1, 7, 255, 256, 257, 600}) {
    std::vector<double> c(length, 2.0), out(length + 1, -7.0);
    for (std::size_t i = 0; i < length; ++i) c[i] = i % 4 == 0 ? -0.5 : (i % 4 == 1 ? NAN : (i % 4 == 2 ? 2.0 : 0.99));
    eval_batch(spec_of(model.lobe()), Tier::exact, std::span<const double>(c), std::span<double>(out).first(length));
    for (std::size_t i = 0; i < length; ++i) {
      if (i % 4 == 1) EXPECT_TRUE(std::isnan(out[i]));
      else EXPECT_NEAR(out[i], lobes::eval(model.lobe(), c[i]), 1e-15) << i;
    }
    EXPECT_EQ(out[length], -7.0) << "wrote past the end";
  }
}

TEST(SimdFormula, UniformStepsAndLetsOfParametersOnly) {
  // A let of parameters only (uniform) and a result that is a parameter: every row gets it.
  expr::Program program({"x"}, {"a"});
  program.let("b", "a^2 + log(a)");
  program.set_result("b + 0*x");
  const std::vector<double> x{1, 2, 3}, params{3};
  std::vector<double> out(3);
  const std::span<const double> inputs[] = {x};
  eval_program(program, inputs, params, out);
  for (const double v : out) EXPECT_NEAR(v, 9 + std::log(3.0), 1e-15);
}

}  // namespace
}  // namespace specula::simd
