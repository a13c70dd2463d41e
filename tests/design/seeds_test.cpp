// The engines' forms refitted (src/design/seeds.h): a reference's numbers and per-material
// subexpressions freed as constants, redundant ones held, and the refit checked against the exact
// height-correlated Smith G₂ evaluated densely in closed form here.
#include <cmath>
#include <gtest/gtest.h>

#include "design/fitting.h"
#include "design/seeds.h"
#include "function_settings.h"
#include "specula/design/design.h"

namespace specula::design {
namespace {

Settings smith() {
  Settings s = function_settings("smith-g2-ggx");
  s.threads = 1;
  return s;
}

int free_constants(const Shape& shape) {
  int n = 0;
  for (const auto& node : shape.nodes) n += node.op == expr::Op::constant && !expr::is_exact(node);
  return n;
}

TEST(Seeds, TheFastSmithFormFreesItsUniformsAndKeepsItsIntegers) {
  const auto seeds = reference_seeds(smith());
  ASSERT_EQ(seeds.size(), 1u) << "fast-smith (the exact term is no form to refit)";
  const Shape& form = seeds[0].shape;
  EXPECT_EQ(seeds[0].reference, "fast-smith");
  // 1 − α and α, twice each; but only the sum of the two 1 − α counts (NoV·NoL·(a + c)): one is
  // held at 0, and its term drops out: NoV·(NoL·a + b) + NoL·d, an operation fewer than the engine's.
  EXPECT_EQ(form.constants, 3) << form.key;
  EXPECT_EQ(free_constants(form), 3);
  EXPECT_EQ(form.key, "fast-smith's form: 2 * NoV * NoL / (7 * NoL + NoV * (7 * NoL + 7))");
  // The first start is the engine's constants at the range's low end, α = 0.05.
  std::vector<double> values, held;
  for (const auto& n : form.nodes)
    if (n.op == expr::Op::constant) (expr::is_exact(n) ? held : values).push_back(n.value);
  EXPECT_EQ(values, (std::vector<double>{0.05, 0.95, 0.05}));
  EXPECT_EQ(held, (std::vector<double>{2}));
}

TEST(Seeds, AConstantTheOthersMakeUpForIsHeld) {
  const auto form = [](const char* text) { return freed_form(expr::parse(text, {"r"}), 1, 0); };
  // 1.04·0.5·r + (1.04·0.0425 + 0.04): two numbers decide it, the other two are held (at 0 or 1
  // where the two left still span the same functions).
  const Shape redundant = without_redundant_constants(form("1.04*(r*0.5 + 0.0425) + 0.04"), 1);
  EXPECT_EQ(redundant.constants, 2) << redundant.key << " / " << expr::to_infix(redundant.expression({"r"}));
  EXPECT_EQ(free_constants(redundant), 2);
  // The control: constants that each move the function are all kept.
  const Shape independent = without_redundant_constants(form("1.04*r^2 + 0.5*r + 0.04"), 1);
  EXPECT_EQ(independent.constants, 3);
  EXPECT_EQ(free_constants(independent), 3);
}

// The fast form refitted at α = 0.05 and α = 0.3 (at α = 1 it is exact) is closer to the exact G₂ than
// the fast form is, on a dense grid of (NoV, NoL) that the fits never saw. (About 2 s.)
TEST(Seeds, TheFastSmithFormRefittedBeatsItsEnginesConstants) {
  const Settings s = smith();
  const Shape form = reference_seeds(s).at(0).shape;
  const auto exact = [](double v, double l, double a) {
    return 2 * v * l / (l * std::sqrt(v * v * (1 - a * a) + a * a) + v * std::sqrt(l * l * (1 - a * a) + a * a));
  };
  const auto fast = [](double v, double l, double a) { return 2 * v * l / (v * (l * (1 - a) + a) + l * (v * (1 - a) + a)); };
  for (const double alpha : {0.05, 0.3}) {
    const Samples rows[] = {samples_at(s, alpha)};
    const GridFit fit = fit_over_grid(form, rows, s);
    ASSERT_TRUE(fit.ok());
    const expr::Expression refit = with_constants(form, fit.constants[0], s.variables);
    double refit_error = 0, fast_error = 0;
    for (int i = 1; i <= 150; ++i)
      for (int j = 1; j <= 150; ++j) {
        const double v = std::pow(i / 150.0, 2), l = std::pow(j / 150.0, 2), x[] = {v, l};
        refit_error = std::max(refit_error, std::abs(expr::evaluate(refit, x) - exact(v, l, alpha)));
        fast_error = std::max(fast_error, std::abs(fast(v, l, alpha) - exact(v, l, alpha)));
      }
    EXPECT_LT(refit_error, 0.6 * fast_error) << "alpha = " << alpha;
  }
}

}  // namespace
}  // namespace specula::design
