// specula fit: symbolic regression on a CSV file (the paper's Figs. 7-8, without TuringBot).
#include <cmath>
#include <fmt/format.h>
#include <iostream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "cli.h"
#include "specula/exceptions.h"
#include "specula/fit/emit.h"
#include "specula/fit/fit.h"
#include "specula/io/csv.h"
#include "specula/io/values.h"
#include "specula/queries/queries.h"

namespace specula::cli {
namespace {

struct FitOptions {
  ModelOptions model;
  std::string n = "paper50";
  std::optional<int> round;
  std::string data, target, vars, ops = "+,*,/", constants = "fitted", weights = "default";
  std::string metric = "rms", split = "random", choose = "parsimonious", snap = "on";
  std::string format = "table", emit, out;
  fit::Options search;
  std::optional<std::int64_t> generations, evaluations;
  std::optional<double> target_error;
  bool quiet = false;
};

// The variables and the target, every value finite (a bad one is named by file line).
fit::Data load_csv(const FitOptions& o) {
  const io::CsvData csv = io::read_csv(o.data);
  fit::Data data;
  std::vector<std::size_t> used;
  const std::size_t target = io::column_index(csv, o.target);
  if (o.vars.empty()) {
    for (std::size_t c = 0; c < csv.columns.size(); ++c)
      if (c != target) used.push_back(c);
  } else {
    for (const auto name : io::split(o.vars, ',')) used.push_back(io::column_index(csv, name));
  }
  if (used.empty()) throw InvalidArgument(fmt::format("{}: no variable columns besides the target", o.data));
  for (std::size_t c : used) {
    if (c == target) throw InvalidArgument(fmt::format("'{}' is both the target and a variable", o.target));
    data.variables.push_back(csv.columns[c]);
    data.columns.push_back(csv.values[c]);
  }
  data.target = csv.values[target];
  used.push_back(target);
  for (std::size_t r = 0; r < data.target.size(); ++r)
    for (std::size_t c : used)
      if (!std::isfinite(csv.values[c][r]))
        throw InvalidArgument(fmt::format("{} line {}: column \"{}\" is {}, every value must be finite",
                                          o.data, csv.lines[r], csv.columns[c], csv.values[c][r]));
  return data;
}

/// --data FILE --target COLUMN, or --model ID: its coefficient k(n) to fit as a function of n.
fit::Data load(const FitOptions& o) {
  if (o.data.empty() == o.model.id.empty())
    throw InvalidArgument("give --data FILE (columns to fit) or --model ID (to fit its normalization k(n)), one of them");
  if (!o.data.empty()) {
    if (o.target.empty()) throw InvalidArgument("--data needs --target COLUMN");
    return load_csv(o);
  }
  if (!o.target.empty() || !o.vars.empty()) throw InvalidArgument("--target and --vars go with --data, not --model");
  const auto n = option_values("--n", o.n, 10'000);
  return queries::normalization_data(o.model.spec(), n, o.round, queries::Spelling::option);
}

/// What was fitted, for the output: the file, or the model's normalization.
std::string source(const FitOptions& o) { return o.data.empty() ? o.model.id + " normalization" : o.data; }
std::string target(const FitOptions& o) { return o.data.empty() ? "coef" : o.target; }

fit::Options search_options(const FitOptions& o) {
  fit::Options s = o.search;
  s.operators = fit::parse_operators(o.ops);
  s.constants = fit::parse_constants(o.constants);
  s.weights = fit::SizeWeights::parse(o.weights);
  s.metric = fit::parse_metric(o.metric);
  const std::optional<fit::Split> split = fit::split_named(o.split);
  if (!split)
    throw InvalidArgument(fmt::format("--split must be {}, got '{}'",
                                      names_listed<fit::Split, fit::kSplitCount>(fit::split_name), o.split));
  s.split = *split;
  s.choice = fit::parse_choice(o.choose);
  s.snap = o.snap == "on";
  s.max_generations = o.generations;
  s.max_evaluations = o.evaluations;
  s.target_error = o.target_error;
  return s;
}

std::string shown(const expr::Expression& e) { return expr::to_infix(fit::rounded(e, 6)); }

std::string error_text(std::optional<double> e) { return e ? fmt::format("{:.6g}", *e) : "-"; }

std::string front_table(const fit::Result& r, fit::Metric metric) {
  const auto m = fit::metric_name(metric);
  std::string text = fmt::format("{:>4}  {:<12}  {:<12}  {}\n", "size", fmt::format("train {}", m),
                                 fmt::format("test {}", m), "formula");
  for (std::size_t i = 0; i < r.front.size(); ++i) {
    const auto& c = r.front[i];
    text += fmt::format("{:>4}  {:<12}  {:<12}  {}{}\n", c.size, error_text(c.train_error),
                        error_text(c.test_error), shown(c.formula), i == r.chosen ? "   <- chosen" : "");
  }
  return text;
}

nlohmann::json front_json(const fit::Result& r, const FitOptions& o) {
  auto entry = [](const fit::Candidate& c) {
    nlohmann::json j{{"size", c.size}, {"train_error", c.train_error},
                     {"test_error", c.test_error ? nlohmann::json(*c.test_error) : nlohmann::json()},
                     {"formula", expr::to_infix(c.formula)}};
    return j;
  };
  nlohmann::json j{{"data", source(o)}, {"target", target(o)}, {"metric", o.metric},
                   {"evaluations", r.evaluations}, {"generations", r.generations},
                   {"seconds", r.seconds}, {"stopped_by", fit::to_string(r.stopped_by)},
                   {"choose", o.choose}, {"front", nlohmann::json::array()}};
  for (const auto& c : r.front) j["front"].push_back(entry(c));
  j["chosen"] = entry(r.front[r.chosen]);
  return j;
}

// The formula's error over every data row.
double error_on(const expr::Expression& formula, const fit::Data& data, fit::Metric metric) {
  std::vector<double> predicted(data.target.size());
  const std::vector<std::span<const double>> columns(data.columns.begin(), data.columns.end());
  expr::evaluate_batch(formula, columns, predicted);
  return fit::measure(metric, predicted, data.target);
}

// The chosen formula as a function in another language, constants at full precision. GLSL
// (float) also states the error with its constants rounded to float.
std::string emitted(const fit::Result& r, const FitOptions& o, const fit::Data& data, fit::Metric metric) {
  const auto& c = r.front[r.chosen];
  std::string origin =
      fmt::format("specula fit: {} from {} ({}), size {}, train {} {:.6g}", target(o), source(o),
                  fmt::join(c.formula.variables(), ", "), c.size, o.metric, c.train_error);
  if (o.emit == "glsl")
    origin += fmt::format("; over all {} rows, {} {:.6g} with float constants (double: {:.6g})", data.target.size(),
                          o.metric, error_on(fit::float_constants(c.formula), data, metric),
                          error_on(c.formula, data, metric));
  return fit::emit_function(c.formula, o.emit, target(o), origin);
}

// On a terminal: the front each time it improves, and a status line.
class ProgressPrinter {
 public:
  explicit ProgressPrinter(fit::Metric metric) : metric_(metric) {}
  void operator()(const fit::Progress& p) {
    std::string front, sizes_and_errors;
    for (const auto& c : *p.front) {
      front += fmt::format("{:>4}  {:<12.6g}  {}\n", c.size, c.train_error, shown(c.formula));
      sizes_and_errors += fmt::format("{} {:.3g} ", c.size, c.train_error);
    }
    std::string out = "\r\033[K";
    if (sizes_and_errors != last_front_)
      out += fmt::format("front after {} evaluations ({:.1f} s), {}:\n{}", p.evaluations,
                         p.elapsed_s, fit::metric_name(metric_), front);
    last_front_ = sizes_and_errors;
    out += fmt::format("{:.1f} s, {:.0f} s left · {} evaluations, {:.0f}/s · generation {}",
                       p.elapsed_s, p.time_left_s, p.evaluations,
                       static_cast<double>(p.evaluations) / std::max(p.elapsed_s, 1e-9), p.generations);
    std::cerr << out << std::flush;
  }
  ~ProgressPrinter() { std::cerr << "\r\033[K" << std::flush; }

 private:
  fit::Metric metric_;
  std::string last_front_;
};

void run(const FitOptions& o) {
  if (o.format != "table" && o.format != "json")
    throw InvalidArgument(fmt::format("--format must be table or json, got '{}'", o.format));
  const fit::Data data = load(o);
  const fit::Options options = search_options(o);
  if (!o.emit.empty() && o.emit != "cpp" && o.emit != "glsl" && o.emit != "latex" && o.emit != "python")
    throw InvalidArgument(fmt::format("--emit must be cpp, glsl, latex or python, got '{}'", o.emit));
  fit::check_emittable(data.variables, o.emit);
  fit::Result result;
  if (!o.quiet && isatty(STDERR_FILENO)) {
    ProgressPrinter printer(options.metric);
    result = fit::search(data, options, std::ref(printer));
  } else {
    result = fit::search(data, options);
  }
  std::string text;
  if (!o.emit.empty())
    text = emitted(result, o, data, options.metric);
  else if (o.format == "json")
    text = front_json(result, o).dump(2) + "\n";
  else
    text = front_table(result, options.metric) +
           fmt::format("{} evaluations, {} generations in {:.1f} s (stopped by {}); chosen: {}\n",
                       result.evaluations, result.generations, result.seconds, fit::to_string(result.stopped_by),
                       o.choose);
  write_output(o.out, text);
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto o = std::make_shared<FitOptions>();
  auto* cmd = app.add_subcommand("fit", "Symbolic regression: find closed-form formulas for a CSV column");
  cmd->add_option("--data", o->data, "CSV file with a header line (at most 256 MiB and 10^6 rows)");
  cmd->add_option("--target", o->target, "The column to fit (with --data)");
  o->model.add_optional_to(*cmd);
  cmd->get_option("--model")->description(
      "Instead of --data: fit this lobe model's exact coefficient k(n) as a function of n (an id, "
      "your own with --models FILE, or inline 'lobe: FORMULA')");
  cmd->add_option("--n", o->n, "With --model: the n values, e.g. 1:1000@50:log or paper50 (at most 10^4)")
      ->capture_default_str();
  cmd->add_option("--round", o->round, "With --model: round k to this many decimals, [0, 17] (as the paper's table)")
      ->check(CLI::Range(0, 17));
  cmd->add_option("--vars", o->vars, "Variable columns, comma-separated (default: every other column)");
  cmd->add_option("--ops", o->ops, "Operators, comma-separated: some of " + fit::operator_names())
      ->capture_default_str();
  cmd->add_option("--constants", o->constants, "fitted | integer (fitted, then rounded) | none")->capture_default_str();
  cmd->add_option("--max-size", o->search.max_size, "Largest formula, in weighted nodes, [1, 100]")
      ->capture_default_str()->check(CLI::Range(1, fit::OptionRanges::max_size));
  cmd->add_option("--size-weights", o->weights, "default (every node 1) | turingbot (÷ = 2) | a list like \"/=2,exp=3\" over the --ops names")
      ->capture_default_str();
  cmd->add_option("--metric", o->metric,
                  names_listed<fit::Metric, fit::kMetricCount>(fit::metric_name, " | ", " | ") +
                      " (max-abs and max-rel fit the constants for the largest error itself: minimax, docs/fit.md)")
      ->capture_default_str();
  cmd->add_option("--test-fraction", o->search.test_fraction, "Rows held out for the test error, in [0, 1)")
      ->capture_default_str();
  cmd->add_option("--split", o->split,
                  "Which rows are held out: " + names_listed<fit::Split, fit::kSplitCount>(fit::split_name, " | ", " | "))
      ->capture_default_str();
  cmd->add_option("--seed", o->search.seed, "Seed of the search and of the random split")->capture_default_str();
  cmd->add_option("--time", o->search.time_limit_s, "Time budget in seconds, (0, 1e6]; Ctrl-C stops at once")
      ->capture_default_str()->check(CLI::Range(1e-9, fit::OptionRanges::time_s));
  cmd->add_option("--generations", o->generations, "Generation budget (per island), ≥ 0");
  cmd->add_option("--evaluations", o->evaluations, "Budget in formulas fitted, ≥ 0");
  cmd->add_option("--target-error", o->target_error, "Stop once a formula's train error is this low (R² this high)");
  cmd->add_option("--threads", o->search.threads, "Threads, [0, 1024]; 0 = all cores (the result does not depend on it)")
      ->capture_default_str()->check(CLI::Range(0, fit::OptionRanges::threads));
  cmd->add_option("--islands", o->search.islands, "Islands of the genetic search, [1, 64]")
      ->capture_default_str()->check(CLI::Range(1, fit::OptionRanges::islands));
  cmd->add_option("--population", o->search.population, "Formulas per island, [4, 20000]")
      ->capture_default_str()->check(CLI::Range(4, fit::OptionRanges::population));
  cmd->add_option("--enumerate-size", o->search.enumerate_max_size,
                  "Enumerate every distinct form up to this size first, [0, 30] (at most 20000 forms)")
      ->capture_default_str()->check(CLI::Range(0, fit::OptionRanges::enumerate_size));
  cmd->add_option("--choose", o->choose,
                  "Which front formula is the answer: " +
                      names_listed<fit::Choice, fit::kChoiceCount>(fit::choice_name, " | ", " | "))
      ->capture_default_str();
  cmd->add_option("--choose-factor", o->search.choose_factor,
                  "parsimonious: the smallest formula within this factor of the best error")
      ->capture_default_str()->check(CLI::Range(1.0, 1e6));
  cmd->add_option("--snap", o->snap,
                  "on | off: try each front formula's constants as simple numbers (0, integers, p/q with q ≤ 12, "
                  "multiples of pi, e, ln 2, sqrt 2, sqrt 3), printed so (1 / 3, 3 * pi / 4)")
      ->capture_default_str()
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--snap-tolerance", o->search.snap_tolerance,
                  "How much a snap may raise a formula's error, relative to it, (0, 1] (default: nothing measurable: "
                  "1e-4 for max-abs and max-rel, min(1e-3, 1/rows) for the other metrics; 0.01 trades 1 % for simpler constants)");
  cmd->add_option("--start", o->search.starts,
                  "A formula to start from besides the search's own (repeatable, e.g. --start '0.5*x^2'): "
                  "its constants are fitted from the values written; it joins the front if it earns a place");
  cmd->add_option("--format", o->format, "table | json")->capture_default_str();
  cmd->add_option("--emit", o->emit, "Print only the chosen formula as a function: cpp | glsl | latex | python");
  cmd->add_option("--out", o->out, "Write to FILE (atomically) instead of stdout");
  cmd->add_flag("--quiet,-q", o->quiet, "No progress on the terminal");
  cmd->footer(
      "Prints the Pareto front: for each size, the most accurate formula found that beats every\n"
      "smaller one, with its train (and test) error. The chosen formula (default rule\n"
      "'parsimonious') is the smallest whose error is within 1.5x of the front's best (test error\n"
      "when rows are held out); 'knee' is the point furthest below the chord of the front in\n"
      "(size, log error); 'best' is the lowest error. Constants are fitted by least squares\n"
      "(exactly where they enter linearly, else Levenberg-Marquardt). Data that are a polynomial,\n"
      "the exp or log of one, or a ratio of two, to rounding, are read off by least squares over\n"
      "the monomials before the search. The same --seed gives the same\n"
      "front for any --threads when the budget is --generations or --evaluations.\n"
      "Examples:\n"
      "  specula normalize --model log --n paper50 --round 3 --out coef.csv\n"
      "  specula fit --data coef.csv --target coef --vars n --size-weights turingbot   # the paper's Fig. 8\n"
      "  specula fit --data coef.csv --target coef --vars n --emit glsl\n"
      "  specula --models my.toml fit --model my-lobe --n 1:1000@50:log   # k(n) of your lobe");
  cmd->callback([o] { run(*o); });
}

}  // namespace specula::cli
