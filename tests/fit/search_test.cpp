// The search end to end: recovery of known formulas, the paper's setting, determinism across
// thread counts, budgets, the train/test split and bad input.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <numbers>
#include <string>
#include <thread>

#include "specula/exceptions.h"
#include "specula/fit/fit.h"
#include "specula/interrupt/interrupt.h"
#include "specula/io/values.h"
#include "specula/lobes/closed_form.h"

namespace specula::fit {
namespace {

Data sampled(const char* truth, double from, double to, std::size_t n) {
  const auto e = expr::parse(truth, {"x"});
  Data d{{"x"}, {{}}, {}};
  for (std::size_t i = 0; i < n; ++i) {
    const double x = from + (to - from) * static_cast<double>(i) / static_cast<double>(n - 1);
    d.columns[0].push_back(x);
    d.target.push_back(expr::evaluate(e, std::vector<double>{x}));
  }
  return d;
}

// Small searches bounded by generations, not time: the suite also runs under sanitizers.
Options quick(std::int64_t generations = 10) {
  Options o;
  o.max_generations = generations;
  o.time_limit_s = 1e4;
  o.enumerate_max_size = 7;
  o.population = 60;
  o.threads = 2;
  return o;
}

// Only `start` and the formulas of one node compete (no genetic search).
Options from_start(const char* operators, const char* start) {
  Options o = quick(0);
  o.enumerate_max_size = 1;
  o.operators = parse_operators(operators);
  o.starts = {start};
  o.transformed_polynomials = false;
  return o;
}

double rms_of(const expr::Expression& f, const Data& d) {
  std::vector<double> predicted(d.target.size());
  const std::vector<std::span<const double>> columns(d.columns.begin(), d.columns.end());
  expr::evaluate_batch(f, columns, predicted);
  return measure(Metric::rms, predicted, d.target);
}

TEST(Search, RecoversARationalFormulaFromNoiselessData) {
  const Data d = sampled("2.5*x + 0.75/(x + 0.5)", 0.1, 5, 40);
  Options o = quick(0);
  o.enumerate_max_size = 9;
  const Result r = search(d, o);
  const auto& chosen = r.front[r.chosen];
  EXPECT_LT(chosen.train_error, 1e-10);
  EXPECT_LE(chosen.size, 9);
}

TEST(Search, GeneticSearchAloneRecoversAFormula) {
  const Data d = sampled("x*x*x*0.5 + 2/x", 0.2, 3, 30);
  Options o = quick(60);
  o.enumerate_max_size = 0;
  const Result r = search(d, o);
  EXPECT_LT(r.front.back().train_error, 1e-10) << expr::to_infix(r.front.back().formula);
}

// Each one-operand op alone recovers itself: y = op(x) is the size-2 formula op(x). Before the
// weight table was sized from the op enum, expm1, log1p and asin read weights past its end.
TEST(Search, EveryUnaryOperatorAloneRecoversItself) {
  for (std::size_t i = 0; i < expr::kOpCount; ++i) {
    const auto op = static_cast<expr::Op>(i);
    if (expr::arity(op) != 1) continue;
    const std::string name = op == expr::Op::neg ? "-" : std::string(expr::function_name(op));
    const Data d = sampled((name + "(x)").c_str(), 0.05, 0.95, 25);
    Options o = quick(3);
    o.operators = {op};
    o.max_size = 4;
    const Result r = search(d, o);
    const auto& best = r.front.back();
    EXPECT_LT(best.train_error, 1e-12) << name << ": " << expr::to_infix(best.formula);
    for (const auto& c : r.front) {
      EXPECT_EQ(c.size, SizeWeights().of(c.formula.nodes())) << name;
      EXPECT_LE(c.size, 4) << name;
    }
  }
}

// A formula's size is its weighted node count, within --max-size, whatever the weights.
TEST(Search, SizesFollowTheWeightsOfEveryOperator) {
  const Data d = sampled("asin(0.5*x) + expm1(x)", 0.05, 0.9, 25);
  Options o = quick(5);
  o.operators = {expr::Op::add, expr::Op::mul, expr::Op::asin, expr::Op::expm1, expr::Op::log1p};
  o.weights = SizeWeights::parse("asin=3,expm1=2,log1p=5");
  o.max_size = 12;
  const Result r = search(d, o);
  ASSERT_FALSE(r.front.empty());
  for (const auto& c : r.front) {
    EXPECT_EQ(c.size, o.weights.of(c.formula.nodes())) << expr::to_infix(c.formula);
    EXPECT_LE(c.size, 12) << expr::to_infix(c.formula);
  }
}

TEST(Search, RecoversAPolynomialWithoutConstants) {
  const Data d = sampled("x*x*x + x*x + x", -1, 1, 20);
  Options o = quick(30);
  o.constants = Constants::none;
  o.operators = {expr::Op::add, expr::Op::sub, expr::Op::mul, expr::Op::div};
  const Result r = search(d, o);
  EXPECT_LT(r.front.back().train_error, 1e-12);
  for (const auto& c : r.front)
    for (const auto& n : c.formula.nodes()) EXPECT_NE(n.op, expr::Op::constant);
}

// The paper's setting (Fig. 8): 50 coefficients rounded to 3 decimals, + × ÷, RMS. TuringBot's
// size-12 formula has RMS 2.80e-4; the enumeration alone reaches that at size ≤ 12.
TEST(Search, MatchesTuringBotOnThePapersRoundedCoefficients) {
  Data d{{"n"}, {io::paper50()}, {}};
  for (double n : d.columns[0]) d.target.push_back(std::round(lobes::log_rv(n) * 1000) / 1000);
  Options o = quick(0);
  o.enumerate_max_size = 11;
  const Result r = search(d, o);
  const auto size12 = std::find_if(r.front.rbegin(), r.front.rend(), [](const Candidate& c) { return c.size <= 12; });
  ASSERT_NE(size12, r.front.rend());
  EXPECT_LE(size12->train_error, 2.8e-4) << expr::to_infix(size12->formula);
}

// Under TuringBot's weights the search meets fits by cancellation (a line drawn as a pole at
// n ≈ 5.6e6 with a 6e12 numerator, n − n + c with 1e10 coefficients); none may reach the front.
TEST(Search, FrontHoldsNoFitsByCancellation) {
  Data d{{"n"}, {io::paper50()}, {}};
  for (double n : d.columns[0]) d.target.push_back(std::round(lobes::log_rv(n) * 1000) / 1000);
  Options o = quick(200);
  o.enumerate_max_size = 11;
  o.weights = SizeWeights::parse("turingbot");
  const Result r = search(d, o);
  for (const auto& c : r.front)
    for (const auto& node : c.formula.nodes())
      EXPECT_LE(std::abs(node.value), 1e6 * 1000) << expr::to_infix(c.formula);
}

// Reported errors are recomputed independently from the printed formula.
TEST(Search, FrontIsParetoOrderedAndItsErrorsAreTrue) {
  const Data d = sampled("exp(0.3*x) + x", 0, 3, 30);
  Options o = quick(5);
  o.operators = {expr::Op::add, expr::Op::mul, expr::Op::div, expr::Op::exp};
  const Result r = search(d, o);
  for (std::size_t i = 0; i < r.front.size(); ++i) {
    const auto& c = r.front[i];
    const auto reparsed = expr::parse(expr::to_infix(c.formula), {"x"});
    EXPECT_NEAR(rms_of(reparsed, d), c.train_error, 1e-9 * std::max(1.0, c.train_error));
    EXPECT_LE(c.size, o.max_size);
    if (i > 0) {
      EXPECT_GT(c.size, r.front[i - 1].size);
      EXPECT_LT(c.train_error, r.front[i - 1].train_error);
    }
  }
}

std::vector<std::pair<std::string, double>> summary(const Result& r) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& c : r.front) out.emplace_back(expr::to_infix(c.formula), c.train_error);
  return out;
}

TEST(Search, SameSeedSameFrontForAnyThreadCount) {
  const Data d = sampled("x*x + 0.3/x", 0.2, 3, 25);
  Options o = quick(10);
  o.islands = 3;
  o.threads = 1;
  const auto one = summary(search(d, o));
  o.threads = 2;
  EXPECT_EQ(summary(search(d, o)), one);
  o.threads = 3;
  EXPECT_EQ(summary(search(d, o)), one);
}

TEST(Search, StopsAtTheTargetErrorOrTheEvaluationBudget) {
  const Data d = sampled("2*x + 1", 0, 1, 10);
  Options o = quick(1000);
  o.target_error = 1e-9;
  EXPECT_EQ(search(d, o).stopped_by, StopReason::target_error);
  const Data hard = sampled("sin(3*x) + x*x", 0, 2, 30);
  Options budget = quick(1000);
  budget.max_evaluations = 3000;
  const Result r = search(hard, budget);
  EXPECT_EQ(r.stopped_by, StopReason::evaluations);
  EXPECT_GE(r.evaluations, 3000);
}

TEST(Search, ACancelledSearchStopsWithTheFrontSoFar) {
  const Data d = sampled("sin(3*x) + x*x", 0, 2, 30);
  Options o = quick(100000);
  std::atomic<bool> cancel = false;
  o.cancel = &cancel;
  int reports = 0;
  const Result r = search(d, o, [&](const Progress& p) {
    ++reports;
    EXPECT_FALSE(p.front->empty());
    cancel = true;  // seen at the next budget check, before the genetic search
  });
  EXPECT_EQ(r.stopped_by, StopReason::cancelled);
  EXPECT_LE(reports, 2);  // the chunk reported, and at most one more
  EXPECT_FALSE(r.front.empty());
  EXPECT_EQ(r.generations, 0);
}

TEST(Search, HeldOutRowsGiveATestError) {
  const Data d = sampled("x*x", 0, 2, 40);
  Options o = quick(3);
  o.test_fraction = 0.25;
  const Result r = search(d, o);
  for (const auto& c : r.front) ASSERT_TRUE(c.test_error.has_value());
  EXPECT_LT(*r.front[r.chosen].test_error, 1e-12);
  o.test_fraction = 0;
  EXPECT_FALSE(search(d, o).front.front().test_error.has_value());
}

// With the last rows held out, a fit on x ≤ 1.5 is tested on x > 1.5: the kink shows.
TEST(Search, LastRowsSplitTestsExtrapolation) {
  Data d = sampled("x", 0, 2, 40);
  for (std::size_t r = 30; r < 40; ++r) d.target[r] = 0;
  Options o = quick(2);
  o.test_fraction = 0.25;
  o.split = Split::last;
  const Result r = search(d, o);
  EXPECT_LT(r.front.back().train_error, 1e-12);
  EXPECT_GT(*r.front.back().test_error, 1.0);
}

TEST(Search, RejectsBadDataAndOptions) {
  const Data good = sampled("x", 0, 1, 10);
  Data nan = good;
  nan.target[3] = std::nan("");
  EXPECT_THROW(search(nan, quick()), InvalidArgument);
  Data ragged = good;
  ragged.columns[0].pop_back();
  EXPECT_THROW(search(ragged, quick()), InvalidArgument);
  EXPECT_THROW(search(Data{{"x"}, {{}}, {}}, quick()), InvalidArgument);
  Options o = quick();
  o.test_fraction = 1;
  EXPECT_THROW(search(good, o), InvalidArgument);
  o = quick();
  o.islands = 0;
  EXPECT_THROW(search(good, o), InvalidArgument);
  o = quick();
  o.max_size = 0;
  EXPECT_THROW(search(good, o), InvalidArgument);
}

// ---- every budget is honoured by every loop (issue: a fit that never stops) ------------------

// Runs the search on another thread; a search still running after `limit` fails the test and
// ends the binary (a hang would otherwise hold it until ctest's timeout).
Result finishes_within(std::chrono::seconds limit, const Data& d, const Options& o) {
  auto running = std::async(std::launch::async, [&] { return search(d, o); });
  if (running.wait_for(limit) != std::future_status::ready) {
    std::fprintf(stderr, "the search did not stop within %lld s\n", static_cast<long long>(limit.count()));
    std::_Exit(1);
  }
  return running.get();
}

Data three_rows() { return Data{{"n"}, {{1, 2, 3}}, {0.3, 0.5, 0.6}}; }

TEST(SearchBudget, AFormulaSpaceSmallerThanThePopulationStopsAtTheTimeBudget) {
  Options o;
  o.operators = parse_operators("+");
  o.max_size = 1;
  o.time_limit_s = 1;
  o.threads = 2;
  const auto start = std::chrono::steady_clock::now();
  const Result r = finishes_within(std::chrono::seconds(60), three_rows(), o);
  EXPECT_EQ(r.stopped_by, StopReason::time);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30);
  EXPECT_FALSE(r.front.empty());
}

TEST(SearchBudget, AFormulaSpaceSmallerThanThePopulationStopsAtTheGenerationBudget) {
  Options o;
  o.operators = parse_operators("+");
  o.max_size = 1;
  o.max_generations = 2;
  o.time_limit_s = 1e4;
  o.threads = 2;
  const Result r = finishes_within(std::chrono::seconds(60), three_rows(), o);
  EXPECT_EQ(r.stopped_by, StopReason::generations);
  EXPECT_EQ(r.generations, 2);
}

// 1000 generations of 2 × 20000 take minutes in any build (2 of them took less than 1 s in a
// release build on an idle machine, which then stopped by generations).
TEST(SearchBudget, AHugePopulationStillStopsAtTheTimeBudget) {
  Options o = quick(1000);
  o.population = OptionRanges::population;
  o.islands = 2;
  o.time_limit_s = 1;
  const auto start = std::chrono::steady_clock::now();
  const Result r = finishes_within(std::chrono::seconds(60), sampled("x*x + 1", 0, 2, 20), o);
  EXPECT_EQ(r.stopped_by, StopReason::time);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30);
}

TEST(SearchBudget, ACancelStopsTheSearchWhileItFillsThePopulation) {
  std::atomic<bool> cancel = false;
  Options o = quick(1'000'000);
  o.population = OptionRanges::population;
  o.cancel = &cancel;
  std::thread canceller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    cancel = true;
  });
  const Result r = finishes_within(std::chrono::seconds(60), sampled("x*x + 1", 0, 2, 20), o);
  canceller.join();
  EXPECT_EQ(r.stopped_by, StopReason::cancelled);
}

TEST(SearchBudget, TheCallersDeadlineCountsAsTheTimeBudget) {
  Options o = quick(1'000'000);
  o.operators = parse_operators("+");
  o.max_size = 1;
  const Data d = three_rows();
  auto running = std::async(std::launch::async, [&] {
    ScopedLimit limit(WorkLimit::after(std::chrono::milliseconds(300)));
    return search(d, o);
  });
  ASSERT_EQ(running.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  EXPECT_EQ(running.get().stopped_by, StopReason::time);
}

TEST(SearchBudget, AStopRequestEndsTheSearchWithInterrupted) {
  Options o = quick(1'000'000);
  std::thread stopper([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    request_stop(SIGINT);
  });
  const Data d = sampled("x*x + 1", 0, 2, 20);
  auto running = std::async(std::launch::async, [&] { return search(d, o); });
  const bool stopped = running.wait_for(std::chrono::seconds(60)) == std::future_status::ready;
  stopper.join();
  clear_stop_request();
  ASSERT_TRUE(stopped);
  EXPECT_THROW(running.get(), Interrupted);
}

TEST(SearchBudget, SizeOptionsOutsideTheirDocumentedRangeAreRefused) {
  const Data d = sampled("x", 0, 1, 10);
  const auto refused = [&](auto change) {
    Options o = quick(0);
    change(o);
    EXPECT_THROW(search(d, o), InvalidArgument);
  };
  refused([](Options& o) { o.islands = OptionRanges::islands + 1; });
  refused([](Options& o) { o.islands = 2147483647; });
  refused([](Options& o) { o.population = OptionRanges::population + 1; });
  refused([](Options& o) { o.enumerate_max_size = 2147483647; });
  refused([](Options& o) { o.max_size = OptionRanges::max_size + 1; });
  refused([](Options& o) { o.threads = 1 << 20; });
  refused([](Options& o) { o.time_limit_s = 1e7; });
  // The controls: the largest values inside the ranges are accepted (and finish).
  Options o = quick(0);
  o.islands = OptionRanges::islands;
  o.population = 4;
  o.enumerate_max_size = OptionRanges::enumerate_size;
  o.max_size = OptionRanges::max_size;
  o.time_limit_s = 30;
  EXPECT_NO_THROW(finishes_within(std::chrono::seconds(240), d, o));
}

// A size option out of its range is InvalidField named by its key (the server's fit field too),
// never by a CLI option: the CLI checks its options against OptionRanges before the search.
TEST(SearchBudget, AnOptionOutsideItsRangeIsNamedByItsKey) {
  const Data d = sampled("x", 0, 1, 10);
  const auto refusal = [&](auto change) {
    Options o = quick(0);
    change(o);
    try {
      search(d, o);
    } catch (const InvalidField& e) {
      return e.field() + ": " + e.what();
    }
    return std::string("no error");
  };
  EXPECT_EQ(refusal([](Options&) {}), "no error");  // control
  EXPECT_EQ(refusal([](Options& o) { o.max_size = 0; }), "max_size: max_size must be in [1, 100], got 0");
  EXPECT_EQ(refusal([](Options& o) { o.enumerate_max_size = 31; }),
            "enumerate_size: enumerate_size must be in [0, 30], got 31");
  EXPECT_EQ(refusal([](Options& o) { o.islands = 65; }), "islands: islands must be in [1, 64], got 65");
  EXPECT_EQ(refusal([](Options& o) { o.population = 3; }), "population: population must be in [4, 20000], got 3");
  EXPECT_EQ(refusal([](Options& o) { o.threads = -1; }), "threads: threads must be in [0, 1024], got -1");
}

}  // namespace
}  // namespace specula::fit

namespace specula::fit {
namespace {

// --metric max-abs fits constants for the largest error itself: the Chebyshev line of eˣ on [0, 1]
// has max error ((e − 1) ln(e − 1) − e + 2)/2 (least squares: 0.1547, minimax_test's control).
TEST(Search, MaxAbsFitsConstantsForTheLargestError) {
  Data d{{"x"}, {{}}, {}};
  for (int i = 0; i <= 1000; ++i) {
    d.columns[0].push_back(i / 1000.0);
    d.target.push_back(std::exp(i / 1000.0));
  }
  Options o;
  o.operators = parse_operators("+,*");
  o.max_size = 5;
  o.metric = Metric::max_abs;
  o.max_generations = 3;
  o.threads = 1;
  o.snap = false;
  const double e = std::numbers::e;
  EXPECT_NEAR(search(d, o).front.back().train_error, ((e - 1) * std::log(e - 1) - e + 2) / 2, 1e-4);
}

/// The chosen formula of y = x²/3 + πx on 41 points, with or without snapping.
std::string chosen_for_third_and_pi(bool snap) {
  Data d{{"x"}, {{}}, {}};
  for (int i = 0; i <= 40; ++i) {
    const double x = i / 10.0;
    d.columns[0].push_back(x);
    d.target.push_back(x * x / 3 + std::numbers::pi * x);
  }
  Options o;  // the formula has size 7: enumerated, then three generations (1 s, against 37 s at 60 and size 11)
  o.max_generations = 3;
  o.enumerate_max_size = 7;
  o.threads = 1;
  o.snap = snap;
  const Result r = search(d, o);
  return expr::to_infix(r.front[r.chosen].formula);
}

TEST(Search, SnappedConstantsPrintAsAThirdAndMultiplesOfPi) {
  const std::string snapped = chosen_for_third_and_pi(true);
  EXPECT_NE(snapped.find("pi"), std::string::npos) << snapped;
  EXPECT_NE(snapped.find("1 / 3"), std::string::npos) << snapped;
  // Negative control: without snapping the same search prints the fitted doubles.
  const std::string fitted = chosen_for_third_and_pi(false);
  EXPECT_EQ(fitted.find("pi"), std::string::npos) << fitted;
}

// e^x on [0, 1] with max-abs and + and ×: the size-5 formula a·(x + b) at its minimax constants
// (max error 0.105933, Chebyshev's equioscillating line). By default no snap may cost measurable
// accuracy: within 0.1 % of that optimum. The control: with the 1 % trade asked for, 12/7 is kept
// and the error is 0.106852 (issue 42's case). (About 2 s under the sanitizers.)
double size5_minimax_error_of_exp(std::optional<double> tolerance, std::string& formula) {
  Data d{{"x"}, {{}}, {}};
  for (int i = 0; i <= 100; ++i) {
    d.columns[0].push_back(i / 100.0);
    d.target.push_back(std::exp(i / 100.0));
  }
  Options o;
  o.metric = Metric::max_abs;
  o.operators = parse_operators("+,*");
  o.max_generations = 2;
  o.enumerate_max_size = 5;
  o.threads = 1;
  o.snap_tolerance = tolerance;
  const Result r = search(d, o);
  for (const auto& f : r.front)
    if (f.size == 5) {
      formula = expr::to_infix(f.formula);
      return f.train_error;
    }
  throw std::runtime_error("no formula of size 5");
}

TEST(Search, ByDefaultASnapCostsNoMeasurableAccuracy) {
  // The minimax line of e^x on [0, 1] (the slope e − 1, equal errors at 0, x* = ln(e − 1) and 1).
  const double slope = std::numbers::e - 1, inner = std::log(slope);
  const double optimum = (1 - slope + slope * inner) / 2;  // |e^0 − b| = |e^x* − slope·x* − b|
  std::string formula;
  const double by_default = size5_minimax_error_of_exp(std::nullopt, formula);
  EXPECT_NEAR(optimum, 0.105933, 1e-6);
  EXPECT_LE(by_default, optimum * 1.001) << formula;
  const double traded = size5_minimax_error_of_exp(0.01, formula);
  EXPECT_GT(traded, optimum * 1.005) << formula;
  EXPECT_NE(formula.find(" / "), std::string::npos) << formula << ": a snapped fraction";
}

// The normal density exp(−x²/2)/√(2π) fitted from 0.4·0.6^(x·x): the fitted 0.398942 and 0.606531
// become their closed forms (identify.h), counted as constants (size 7, as the decimals' formula).
// The control: with snapping off the decimals stay.
std::pair<std::string, int> chosen_for_the_normal_density(bool snap) {
  const Data d = sampled("exp(-x^2/2) / sqrt(2*pi)", -2, 2, 41);
  Options o = from_start("+,*,^", "0.4 * 0.6 ^ (x * x)");
  o.snap = snap;
  const Result r = search(d, o);
  return {expr::to_infix(r.front[r.chosen].formula), r.front[r.chosen].size};
}

TEST(Search, ElementaryConstantsPrintInClosedForm) {
  const auto [snapped, size] = chosen_for_the_normal_density(true);
  EXPECT_EQ(snapped, "exp(-1 / 2) ^ x ^ 2 / sqrt(2 * pi)");
  EXPECT_EQ(size, 7);
  const auto [fitted, fitted_size] = chosen_for_the_normal_density(false);
  EXPECT_EQ(fitted.find("pi"), std::string::npos) << fitted;
  EXPECT_NE(fitted.find("0.398942"), std::string::npos) << fitted;
  EXPECT_EQ(fitted_size, 7);
}

// 4x⁴ + 3x³ + 2x² + x found factored over its real roots, 4·x·(x + 0.60583)·((x + 0.0720852)² +
// 0.407461) (size 15, bench-fit's Livermore-6): exact as fitted, but its printed constants are not.
// Multiplied out, its coefficients snap to integers (size 19), and the front, ranking formulas as
// printed, keeps both and chooses the exact one. Control: without the ^ that writes the expansion
// the factored form stays the choice.
std::string chosen_for_a_factored_quartic(const char* operators) {
  const Data d = sampled("4*x^4 + 3*x^3 + 2*x^2 + x", -1, 1, 21);
  Options o = from_start(operators, "4 * x * (x + 0.6) * ((x + 0.07) * (x + 0.07) + 0.4)");
  const Result r = search(d, o);
  return expr::to_infix(r.front[r.chosen].formula);
}

TEST(Search, APolynomialFoundFactoredIsChosenExpandedWhereItsCoefficientsSnap) {
  EXPECT_EQ(chosen_for_a_factored_quartic("+,*,^"), "x + 2 * x ^ 2 + 3 * x ^ 3 + 4 * x ^ 4");
  const std::string control = chosen_for_a_factored_quartic("+,*");
  EXPECT_NE(control.find("0.605829"), std::string::npos) << control;
}

// bench-fit's Keijzer-5 seed 2 ended as 10·x·z/y²/(1/3·x − 10/3), size 15 > 13: found as
// x/(x/3 − 10/3) − 3, whose x terms cancel only once snapped, and simplified after the snap, so the
// free scale of 10/(x/3 − 10/3) was never held. The simplified snap is snapped again.
TEST(Search, AFormulaSimplifiedAfterItsSnapIsSnappedAgain) {
  const Data d = sampled("30 / (x - 10)", 0, 5, 21);
  Options o = from_start("+,-,*,/", "x / (0.3 * x - 3.2) - 2.9");
  const Result r = search(d, o);
  EXPECT_EQ(expr::to_infix(r.front[r.chosen].formula), "30 / (x - 10)");
  EXPECT_EQ(r.front[r.chosen].size, 5);
}

// bench-fit's Keijzer-14, 8/(2 + x² + y²): 11 nodes the genetic search meets only by chance
// (it found the truth in 2 of 12 runs) and the enumeration does not reach (20 000 forms end
// before size 11 with two variables); the reciprocal of the target is a quadratic, read off the
// data by least squares.
TEST(Search, ReadsAFormulaOffTheDataWhereATransformIsAPolynomial) {
  Data d{{"x", "y"}, {{}, {}}, {}};
  for (int i = 0; i < 20; ++i) {
    const double x = -3 + 0.29 * i, y = 2.7 * std::sin(1.7 * i);
    d.columns[0].push_back(x);
    d.columns[1].push_back(y);
    d.target.push_back(8 / (2 + x * x + y * y));
  }
  Options o = quick(0);
  o.operators = parse_operators("+,-,*,/,sin,cos,exp,log,^");
  o.enumerate_max_size = 3;
  const Result r = search(d, o);
  EXPECT_EQ(expr::to_infix(r.front[r.chosen].formula), "8 / (x ^ 2 + y ^ 2 + 2)");
  EXPECT_EQ(r.front[r.chosen].size, 11);
  o.transformed_polynomials = false;  // control
  const Result without = search(d, o);
  EXPECT_GT(without.front[without.chosen].train_error, 1e-6);
}

// The outside check's bad formulas, given as starts, do not reach the front: cancellations (of
// constants, of huge terms), garbage terms, integers and halves in disguise.
const std::vector<std::string> kBadStarts = {
    "1573607.28 - 0.99999936 ^ x * 1573606.29",
    "x ^ 3.999999999999996 + 0.5000000000000001",
    "x ^ 4 + 0.5 - 8.99e-16 / cos(x)",
    "(1.3123802532262523 - 1.3123802532262514) * x + x ^ 4 + 0.4999999999999998",
    "(x ^ 0.395) ^ 10.126582278481013 + 0.5",
    "1e7 * x - 1e7 * (x - 5e-8) + x ^ 4",
};

/// Whether a formula's text shows one of the defects above.
bool looks_bad(const std::string& text) {
  for (const char* sign : {"1573", "e-1", "99999", "00000", "0.395", "1e7", "1e+07", "10000000"})
    if (text.find(sign) != std::string::npos) return true;
  return false;
}

TEST(Search, BadFormulasGivenAsStartsNeverReachTheFront) {
  const Data d = sampled("x^4 + 0.5", 0.1, 2, 30);
  Options o = quick(3);
  o.operators = parse_operators("+,-,*,/,^,cos");
  o.starts = kBadStarts;
  const Result r = search(d, o);
  for (const auto& c : r.front) EXPECT_FALSE(looks_bad(expr::to_infix(c.formula))) << expr::to_infix(c.formula);
  EXPECT_EQ(expr::to_infix(r.front[r.chosen].formula), "x ^ 4 + 0.5");
  for (const auto& start : kBadStarts) EXPECT_TRUE(looks_bad(start)) << start;  // negative control
}

// Where nothing else competes (no genetic search, only x and c enumerated) and the data are the
// cancelling formula's own values (its constants within the 1e6·scale limit), it still stays off
// the front: 6 of its digits are rounding on every row.
TEST(Search, ACancellingStartStaysOffTheFrontEvenWhereItFitsBest) {
  const Data d = sampled("1573607.28 - 0.99999936 ^ x * 1573606.29", 0, 1, 21);
  Options o = from_start("+,-,*,^", "1573607.28 - 0.99999936 ^ x * 1573606.29");
  o.snap = false;
  const Result r = search(d, o);
  for (const auto& c : r.front) EXPECT_LE(c.size, 1) << expr::to_infix(c.formula);
}

TEST(Search, AnUnreadableStartIsRefusedByKey) {
  const Data d = sampled("x", 0, 1, 5);
  Options o = quick(1);
  o.starts = {"x +"};
  try {
    search(d, o);
    FAIL() << "'x +' was accepted";
  } catch (const InvalidField& e) {
    EXPECT_EQ(e.field(), "starts");
  }
}

TEST(Search, SnapToleranceOutsideItsRangeIsRefusedByKey) {
  Data d{{"x"}, {{1, 2, 3}}, {1, 2, 3}};
  Options o;
  o.snap_tolerance = 0;
  try {
    search(d, o);
    FAIL() << "snap_tolerance 0 was accepted";
  } catch (const InvalidField& e) {
    EXPECT_EQ(e.field(), "snap_tolerance");
  }
}

}  // namespace
}  // namespace specula::fit
