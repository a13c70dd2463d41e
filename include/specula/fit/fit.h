#pragma once
// Symbolic regression: closed-form formulas y ≈ f(x₁, …) found by an exhaustive, deduplicated
// enumeration of small expressions followed by genetic programming on islands. Every candidate's
// numeric constants are fitted: constants that enter linearly are solved exactly by least
// squares, the others by Levenberg–Marquardt (variable projection). The result is the Pareto
// front of size against error. With the same seed and budgets in generations or evaluations the
// front is the same for any thread count (a time budget stops at a machine-dependent epoch).
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "specula/expr/expr.h"

namespace specula::fit {

/// The error a formula is ranked by: RMS, mean absolute, maximum absolute |f − y|, maximum
/// relative |f − y|/|y|, mean relative, or R² (reported as R², ranked by 1 − R²). Constants are
/// fitted in least squares (weighted by 1/y² for the relative errors); for max_abs and max_rel the
/// least-squares fit is then refined for the maximum error itself (minimax, docs/fit.md).
enum class Metric { rms, mae, max_abs, max_rel, mean_relative, r2 };
inline constexpr std::size_t kMetricCount = static_cast<std::size_t>(Metric::r2) + 1;  // r2: the last
Metric parse_metric(std::string_view name);  // "rms", "mae", "max-abs", "max-rel", "mean-relative", "r2"
std::string_view metric_name(Metric metric);

/// The metric as a loss, lower is better: 1 − R² for r2, the metric itself otherwise.
double to_loss(Metric metric, double error);

/// The metric of `predicted` against `target` (same length, non-empty); nan inputs give inf.
double measure(Metric metric, std::span<const double> predicted, std::span<const double> target);

/// fitted: real constants fitted to the data; integer: fitted, then rounded to integers;
/// none: formulas are built from the variables alone.
enum class Constants { fitted, integer, none };
inline constexpr std::size_t kConstantsCount = static_cast<std::size_t>(Constants::none) + 1;  // none: the last
Constants parse_constants(std::string_view name);  // "fitted", "integer", "none"
std::string_view constants_name(Constants constants);

/// How much each node adds to a formula's size (integers ≥ 1; leaves count 1).
class SizeWeights {
 public:
  SizeWeights();  // every node counts 1
  /// "default", "turingbot" (÷ counts 2, as the paper's tool appears to), or a list of overrides
  /// such as "/=2,sqrt=3,exp=2" on top of the default.
  static SizeWeights parse(std::string_view text);
  int of(expr::Op op) const { return weight_[static_cast<std::size_t>(op)]; }
  int of(std::span<const expr::Node> nodes) const;
  void set(expr::Op op, int weight);

 private:
  std::array<int, expr::kOpCount> weight_{};
};

/// Parses an operator list such as "+,*,/" or "+,-,*,/,sin,cos,exp,log" (names as in expr).
std::vector<expr::Op> parse_operators(std::string_view text);
/// Every name parse_operators() and SizeWeights::parse() take, space-separated: "+ - * / ^ pow …".
std::string operator_names();

/// Which rows are held out for the test error: drawn at random (with the seed), or the last ones.
enum class Split { random, last };
inline constexpr std::size_t kSplitCount = static_cast<std::size_t>(Split::last) + 1;  // last: the last
std::optional<Split> split_named(std::string_view name);  // "random", "last"
std::string_view split_name(Split split);

/// Which formula of the front is reported as the answer.
///  parsimonious: the smallest whose error (test error when there is a test set; the printed
///                formula's where that is larger) is within `choose_factor` of the front's best,
///                or below the data's noise floor (noise_floor()) — accuracy first, then size.
///  knee:         the point furthest below the chord from the smallest to the most accurate
///                formula, in (size, log error) scaled to the unit square.
///  best:         the lowest error.
enum class Choice { parsimonious, knee, best };
inline constexpr std::size_t kChoiceCount = static_cast<std::size_t>(Choice::best) + 1;  // best: the last
Choice parse_choice(std::string_view name);  // "parsimonious", "knee", "best"
std::string_view choice_name(Choice choice);

/// The documented range of each size-like option: search() refuses values outside with
/// InvalidArgument. Within them memory stays below ~2 GiB (populations, per-island caches and
/// the enumeration are bounded) and every loop of the search looks at the time budget, the
/// cancel flag and a stop request at least every few thousand formula evaluations.
/// An option out of its range is InvalidField named by its key (max_size, islands, population,
/// enumerate_size, threads), the name the server's fit request gives it too.
struct OptionRanges {
  static constexpr int max_size = 100;            ///< max_size in [1, 100]
  static constexpr int islands = 64;              ///< islands in [1, 64]
  static constexpr int population = 20'000;       ///< population in [4, 20000]
  static constexpr int enumerate_size = 30;       ///< enumerate_size (enumerate_max_size) in [0, 30]
  static constexpr int enumerate_limit = 1'000'000;
  static constexpr int threads = 1024;            ///< threads in [0, 1024]
  static constexpr double time_s = 1e6;           ///< time_limit_s in (0, 1e6] seconds
  static constexpr std::size_t rows = 1'000'000;  ///< data rows
  static constexpr double snap_tolerance = 1;     ///< snap_tolerance in (0, 1]
  static constexpr std::size_t starts = 1000;     ///< starts: at most 1000 formulas
};

struct Options {
  std::vector<expr::Op> operators = {expr::Op::add, expr::Op::mul, expr::Op::div};
  Constants constants = Constants::fitted;
  int max_size = 25;
  SizeWeights weights;
  Metric metric = Metric::rms;
  double test_fraction = 0;  // in [0, 1): rows held out for the test error
  Split split = Split::random;
  std::uint64_t seed = 1;  // search and random split
  double time_limit_s = 60;
  std::optional<std::int64_t> max_generations;
  std::optional<std::int64_t> max_evaluations;
  std::optional<double> target_error;  // stop once a formula's train error is at most this
  int threads = 0;                     // 0: all cores
  int islands = 4;
  int population = 200;        // per island
  int enumerate_max_size = 11;  // exhaustive up to this size …
  int enumerate_limit = 20000;  // … or this many distinct forms, whichever comes first
  /// Formulas read off the data before the genetic search (docs/fit.md, "Transformed
  /// polynomials"): a polynomial P, exp(P), log(P) or a ratio P/Q that fits the target to
  /// rounding, by least squares over the monomials; they join the front (not the populations).
  bool transformed_polynomials = true;
  Choice choice = Choice::parsimonious;
  double choose_factor = 1.5;
  /// Constant snapping (docs/fit.md): each front formula's constants tried as simple numbers (0,
  /// integers, p/q with q ≤ 12, p·s/q for s = π, e, ln 2, √2, √3 and q ≤ 6), each kept where the error rises by
  /// at most snap_tolerance of itself (or stays below the target error or rounding). Unset: only
  /// snaps that cost nothing measurable (free_snap_tolerance).
  bool snap = true;
  std::optional<double> snap_tolerance;  ///< in (0, 1] where set
  /// Formulas over the data's variables the search starts from besides its own (at most
  /// OptionRanges::starts, each within max_size): their constants are fitted from the values
  /// written, they are simplified like any candidate, and they join the front and the
  /// populations. An unreadable one is InvalidField "starts".
  std::vector<std::string> starts;
  /// When set, the search stops at its next budget check (within an enumeration chunk, a
  /// population or a generation) with stopped_by cancelled and the front found so far. The
  /// calling thread's work limit (specula/interrupt) counts too: its cancel flag as a cancel, its
  /// deadline as the time budget. A process-wide stop request throws Interrupted.
  const std::atomic<bool>* cancel = nullptr;
};

/// Rows of named variables and a target. Every column has the same, non-zero length; values
/// are finite (checked by search()).
/// The snap tolerance when none is given: a snap costs nothing measurable. For the minimax metrics
/// (max-abs, max-rel) 10⁻⁴ of the error (the constants stay within 0.1 % of the minimax optimum's
/// error, as a user asking for a minimax fit expects); for the others min(10⁻³, 1/rows) of the loss — 1/rows is what
/// one constant fitted to noise lowers it by, on average, so the snapped formula is as likely as
/// not the truth (noise-free data lands at rounding, where any right snap costs nothing).
double free_snap_tolerance(Metric metric, std::size_t rows);

struct Data {
  std::vector<std::string> variables;
  std::vector<std::vector<double>> columns;
  std::vector<double> target;
};

struct Candidate {
  expr::Expression formula;
  int size = 0;
  double train_error = 0;
  std::optional<double> test_error;
  /// The error (on the test rows where there are some) of the formula as printed: its fitted
  /// constants rounded to kPrintedDigits significant digits. Large constants that cancel lose
  /// their accuracy there; the choice ranks by the larger of the two.
  std::optional<double> printed_error = std::nullopt;
};

/// The significant digits the tables print a fitted constant with.
inline constexpr int kPrintedDigits = 6;

struct Progress {
  double elapsed_s = 0;
  double time_left_s = 0;
  std::int64_t evaluations = 0;
  std::int64_t generations = 0;
  const std::vector<Candidate>* front = nullptr;
};

/// What stopped a search: its time budget, its generation or evaluation budget, a formula as
/// accurate as the target error, or a cancel.
enum class StopReason { time, generations, evaluations, target_error, cancelled };
inline constexpr std::size_t kStopReasonCount = static_cast<std::size_t>(StopReason::cancelled) + 1;  // cancelled: the last
/// "time", "generations", "evaluations", "target error" or "cancelled".
std::string_view to_string(StopReason reason);

struct Result {
  std::vector<Candidate> front;  // ascending size, each more accurate on the training rows
  std::size_t chosen = 0;        // index into front
  std::int64_t evaluations = 0;  // formulas whose constants were fitted and error measured
  std::int64_t generations = 0;
  double seconds = 0;
  StopReason stopped_by = StopReason::time;
};

/// Throws InvalidArgument on bad data or options (each message names the problem).
Result search(const Data& data, const Options& options,
              const std::function<void(const Progress&)>& on_progress = {});

/// A formula with its constants fitted, and its error on the data in the metric fitted for.
struct FittedFormula {
  expr::Expression formula;
  double error = 0;
};
/// `formula`'s plain constants fitted to `data` for `metric`, from the values written (exact
/// constants stay), as search() fits every candidate: least squares (weighted by 1/y² for the
/// relative metrics), then minimax for max_abs and max_rel. The formula's variables are the
/// data's, in order. Throws InvalidArgument on data search() would refuse (no rows, columns of
/// other lengths, non-finite values, a zero target under a relative metric) or more than 64
/// constants.
FittedFormula fit_formula_constants(const expr::Expression& formula, const Data& data, Metric metric);

/// The index of the formula `choice` picks from a non-empty front (errors in `metric`, each
/// formula's the larger of its error and its printed error). `noise_floor` (a loss): errors below
/// it are all "fits the data", among which parsimony takes the smallest.
std::size_t choose(const std::vector<Candidate>& front, Metric metric, Choice choice,
                   double factor, double noise_floor);

/// The loss below which a formula fits `target` to its noise: 1e-10 of its RMS, or the rounding
/// of its decimals (values with 3 decimals: 0.001/√12) where `best_loss`, the front's best, does
/// not go below that (exact data that happen to be round numbers go below it).
double noise_floor(std::span<const double> target, Metric metric, double best_loss);

/// `e` with every constant rounded to `digits` significant digits, for display (an exact constant,
/// 1/3 or π/4, stays as it is).
expr::Expression rounded(const expr::Expression& e, int digits);

/// `e` with its constants as a float shader has them: a plain one rounded to the nearest float, an
/// exact one p·s/q computed in float as its GLSL text reads ((p · s) / q). Its error on the data
/// is what `--emit glsl` reports beside the double one.
expr::Expression float_constants(const expr::Expression& e);

}  // namespace specula::fit
