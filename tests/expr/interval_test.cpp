// Interval enclosures (include/specula/expr/interval.h): for every op, on random boxes, every value
// the expression takes at points drawn inside the box lies in both enclosures; the control shows
// the check catches an interval that is not an enclosure.
#include <cmath>
#include <gtest/gtest.h>
#include <random>

#include "specula/expr/expr.h"
#include "specula/expr/interval.h"

namespace specula::expr {
namespace {

// Whether `enclosure` holds e at `samples` random points of the box (NaN values are not checked:
// the enclosure of an op outside its domain is the whole line anyway).
bool encloses(const Expression& e, const std::vector<Interval>& box, Interval enclosure, std::mt19937_64& rng, int samples = 300) {
  std::vector<double> x(box.size());
  for (int i = 0; i < samples; ++i) {
    for (std::size_t v = 0; v < box.size(); ++v) x[v] = std::uniform_real_distribution<double>(box[v].lo, box[v].hi)(rng);
    if (i == 0)
      for (std::size_t v = 0; v < box.size(); ++v) x[v] = box[v].lo;  // the corners count too
    const double value = evaluate(e, x);
    if (std::isnan(value)) continue;
    if (!(value >= enclosure.lo && value <= enclosure.hi)) return false;
  }
  return true;
}

TEST(Interval, EveryOpIsEnclosedOnRandomBoxes) {
  const char* formulas[] = {
      "x + y", "x - y", "x * y", "x / y", "x ^ 2", "x ^ 3", "x ^ -2", "x ^ y", "min(x, y)", "max(x, y)", "-x",
      "log(x)", "log2(x)", "exp(x)", "sqrt(x)", "abs(x)", "sin(x)", "cos(x)", "acos(x)", "asin(x)", "expm1(x)",
      "log1p(x)", "x * (1 - x) / (x + y * y)", "sqrt(x ^ 2 * (1 - y ^ 2) + y ^ 2)", "exp(-x * y) * sin(3 * x + y)",
      "fresnel_dielectric(x, 1.5 + y)"};
  std::mt19937_64 rng(7);
  for (const char* text : formulas) {
    const Expression e = parse(text, {"x", "y"});
    for (int trial = 0; trial < 60; ++trial) {
      std::vector<Interval> box(2);
      for (auto& side : box) {
        const double scale = trial % 3 == 0 ? 8 : trial % 3 == 1 ? 1 : 0.01;
        double a = std::uniform_real_distribution<double>(-scale, scale)(rng), b = a + std::uniform_real_distribution<double>(0, scale)(rng);
        if (trial % 2) a = std::abs(a), b = a + std::abs(b - a);  // positive boxes, where logs and roots live
        side = {a, b};
      }
      EXPECT_TRUE(encloses(e, box, evaluate_interval(e, box), rng)) << text << " natural, trial " << trial;
      EXPECT_TRUE(encloses(e, box, evaluate_mean_value(e, box), rng)) << text << " mean value, trial " << trial;
    }
  }
}

TEST(Interval, TheCheckCatchesWhatIsNotAnEnclosure) {  // the negative control of the test above
  std::mt19937_64 rng(7);
  const Expression square = parse("x ^ 2", {"x"});
  const std::vector<Interval> box{{-1, 1}};
  const double ends[] = {-1}, other[] = {1};
  const Interval at_ends{std::min(evaluate(square, ends), evaluate(square, other)), std::max(evaluate(square, ends), evaluate(square, other))};
  EXPECT_FALSE(encloses(square, box, at_ends, rng)) << "x² over [−1, 1] reaches 0, between its ends' 1 and 1";
  EXPECT_EQ(evaluate_interval(square, box).lo, 0);
}

TEST(Interval, TheMeanValueFormIsTighterOnASmallBox) {
  const Expression e = parse("x * (1 - x) * (x + 1)", {"x"});
  const std::vector<Interval> box{{0.4, 0.41}};
  const Interval natural = evaluate_interval(e, box), mean_value = evaluate_mean_value(e, box);
  EXPECT_LT(mean_value.hi - mean_value.lo, 0.6 * (natural.hi - natural.lo));
  EXPECT_GE(mean_value.lo, natural.lo);
  EXPECT_LE(mean_value.hi, natural.hi);
}

TEST(Interval, OutsideAnOpsDomainTheEnclosureIsTheWholeLine) {
  const std::vector<Interval> spanning{{-1, 1}};
  EXPECT_TRUE(evaluate_interval(parse("1 / x", {"x"}), spanning).whole());
  EXPECT_TRUE(evaluate_interval(parse("log(x)", {"x"}), spanning).whole());
  EXPECT_TRUE(evaluate_interval(parse("sqrt(x)", {"x"}), spanning).whole());
  EXPECT_FALSE(evaluate_interval(parse("sqrt(x)", {"x"}), std::vector<Interval>{{0, 1}}).whole());
}

}  // namespace
}  // namespace specula::expr
