// Minimax constant fitting (fit_constants with max_abs or max_rel) against answers known in
// closed form, with least squares as the negative control.
#include "fit/constants.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace specula::fit {
namespace {

using std::numbers::e;

struct Samples {
  std::vector<double> x, y;
  Rows rows() const { return {{x}, y, {}}; }
};

// `count` evenly spaced points of f on [lo, hi], both ends included.
Samples sampled(double (*f)(double), double lo, double hi, int count) {
  Samples s;
  for (int i = 0; i < count; ++i) {
    s.x.push_back(lo + (hi - lo) * i / (count - 1));
    s.y.push_back(f(s.x.back()));
  }
  return s;
}

Genome minimax_genome(std::string_view text) {
  const auto formula = expr::parse(text, {"x"});
  return {formula.nodes().begin(), formula.nodes().end()};
}

// The form's error in `measured` once its constants are fitted for `fitted_for`.
double fitted_error(std::string_view form, const Samples& s, Metric fitted_for, Metric measured) {
  Genome g = minimax_genome(form);
  return measure(measured, fit_constants(g, s.rows(), Constants::fitted, fitted_for), s.y);
}

const Samples kExp = sampled([](double x) { return std::exp(x); }, 0, 1, 1001);

// The best uniform line a + b·x for eˣ on [0, 1] touches its largest error E at 0, ln(e − 1) and
// 1 with alternating signs: b = e − 1, E = ((e − 1)·ln(e − 1) − e + 2)/2 ≈ 0.105933.
const double kChebyshevLineError = ((e - 1) * std::log(e - 1) - e + 2) / 2;

TEST(Minimax, FitsTheChebyshevLineOfExp) {
  Genome g = minimax_genome("1 + 1*x");
  const auto predicted = fit_constants(g, kExp.rows(), Constants::fitted, Metric::max_abs);
  EXPECT_NEAR(measure(Metric::max_abs, predicted, kExp.y), kChebyshevLineError, 1e-4);
  EXPECT_NEAR(g[1].value, e - 1, 1e-3);
}

// The negative control: the least-squares line's largest error is about 0.1547, far from E.
TEST(Minimax, LeastSquaresMissesTheChebyshevLine) {
  const double error = fitted_error("1 + 1*x", kExp, Metric::rms, Metric::max_abs);
  EXPECT_NEAR(error, 0.1547, 1e-3);
  EXPECT_GT(std::abs(error - kChebyshevLineError), 1e-4);
}

// The same line written with a constant that enters nonlinearly: (a + x)·b.
TEST(Minimax, FitsTheChebyshevLineThroughNonlinearConstants) {
  EXPECT_NEAR(fitted_error("(1 + x)*1", kExp, Metric::max_abs, Metric::max_abs), kChebyshevLineError, 1e-4);
}

// A constant c for y = x on [1, 4]: the largest relative error |c − y|/y is lowest where
// (c − 1)/1 = (4 − c)/4, c = 1.6 with 0.6; the largest absolute error where c = 2.5, with 1.5.
const Samples kLine = sampled([](double x) { return x; }, 1, 4, 301);

TEST(Minimax, MaxRelMinimizesTheLargestRelativeError) {
  Genome g = minimax_genome("1");
  const auto predicted = fit_constants(g, kLine.rows(), Constants::fitted, Metric::max_rel);
  EXPECT_NEAR(g[0].value, 1.6, 1e-9);
  EXPECT_NEAR(measure(Metric::max_rel, predicted, kLine.y), 0.6, 1e-9);
  EXPECT_NEAR(fitted_error("exp(0)", kLine, Metric::max_rel, Metric::max_rel), 0.6, 1e-6);  // c = exp(k): nonlinear

  Genome absolute = minimax_genome("1");
  fit_constants(absolute, kLine.rows(), Constants::fitted, Metric::max_abs);
  EXPECT_NEAR(absolute[0].value, 2.5, 1e-9);
  EXPECT_GT(fitted_error("1", kLine, Metric::rms, Metric::max_rel), 0.6 + 0.1);
}

// No formula of the form does better: the relative error of the max-rel line for eˣ is no larger
// than that of the max-abs line or of least squares, and it equioscillates like a minimax fit.
TEST(Minimax, MaxRelLineForExpBeatsTheOtherFits) {
  const double relative = fitted_error("1 + 1*x", kExp, Metric::max_rel, Metric::max_rel);
  for (Metric other : {Metric::rms, Metric::max_abs}) {
    Genome g = minimax_genome("1 + 1*x");
    const auto predicted = fit_constants(g, kExp.rows(), Constants::fitted, other);
    EXPECT_LT(relative, measure(Metric::max_rel, predicted, kExp.y)) << metric_name(other);
  }
  Genome g = minimax_genome("1 + 1*x");
  const auto predicted = fit_constants(g, kExp.rows(), Constants::fitted, Metric::max_rel);
  EXPECT_NEAR(std::abs(predicted.front() - 1), relative, 1e-9);      // at x = 0, …
  EXPECT_NEAR(std::abs(predicted.back() - e) / e, relative, 1e-9);   // … and at x = 1
}

TEST(Minimax, ZeroTargetsLeaveMaxRelToLeastSquares) {
  const Samples s = sampled([](double x) { return x; }, -1, 1, 21);
  Genome least_squares = minimax_genome("1 + 1*x"), relative = least_squares;
  fit_constants(least_squares, s.rows(), Constants::fitted, Metric::rms);
  fit_constants(relative, s.rows(), Constants::fitted, Metric::max_rel);
  EXPECT_EQ(relative[0].value, least_squares[0].value);
  EXPECT_EQ(relative[1].value, least_squares[1].value);
}

TEST(Minimax, MaxRelNameRoundTrips) {
  EXPECT_EQ(parse_metric("max-rel"), Metric::max_rel);
  EXPECT_EQ(metric_name(Metric::max_rel), "max-rel");
  const std::vector<double> f{1.5, 2, 3}, y{1, 4, 3};
  EXPECT_DOUBLE_EQ(measure(Metric::max_rel, f, y), 0.5);
  EXPECT_EQ(measure(Metric::max_rel, std::vector<double>{0, 1}, std::vector<double>{0, 0}), INFINITY);
  EXPECT_EQ(to_loss(Metric::max_rel, 0.25), 0.25);
}

}  // namespace
}  // namespace specula::fit
