// The search: exhaustive enumeration of small forms and the formulas linear algebra reads off
// exact data (transformed.h), then genetic programming on islands with Pareto (size, error)
// selection. Islands own their random streams and run in lockstep epochs; the archive and
// migrations are updated between epochs in island order, so results do not depend on how many
// threads ran the islands.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <numeric>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/info.h>
#include <oneapi/tbb/task_arena.h>
#include <unordered_map>
#include <unordered_set>

#include "constants.h"
#include "expanded.h"
#include "genome.h"
#include "simplified.h"
#include "snap.h"
#include "transformed.h"
#include "specula/fit/fit.h"
#include "specula/interrupt/interrupt.h"

namespace specula::fit {

using expr::Node;
using expr::Op;

namespace {

struct Individual {
  Genome genome;
  std::string key;
  double loss = INFINITY;
  int size = 0;
  bool cancels = false;  // fits by cancellation: may breed, never enters the front
  double printed_loss = 0;  // the loss with the constants as printed (snapped front only)

  // What the front ranks by: the formula as fitted, or as a reader copies it, whichever is worse.
  double ranking() const { return std::max(loss, printed_loss); }
};

bool better(const Individual& a, const Individual& b) {
  return a.loss < b.loss || (a.loss == b.loss && a.size < b.size);
}

// The data split into the rows constants are fitted on and the rows held out.
struct Problem {
  std::vector<std::vector<double>> train_columns, test_columns;
  std::vector<double> train_target, test_target;
  Rows train;
  Metric metric;
  Constants constants;
  SizeWeights weights;

  double largest_constant = INFINITY;
  SimplifyRules rules;

  // `key` is canonical_key(formula), which folding constants does not change.
  Individual evaluate(const Genome& formula, std::string key) const {
    Genome g = folded_constants(formula);
    const auto predicted = fit_constants(g, train, constants, metric);
    if (auto simple = simplified(g, predicted, train, rules)) {  // the same values, fewer nodes
      g = std::move(*simple);
      key = canonical_key(g);
    }
    Individual out{std::move(g), std::move(key), to_loss(metric, measure(metric, predicted, train_target)), 0};
    if (std::isnan(out.loss)) out.loss = INFINITY;
    out.cancels = cancels(out.genome);
    out.size = weights.of(out.genome);
    return out;
  }

  // A fit that works by cancellation: a fitted constant far beyond the data's scale (a line
  // drawn as a far-off pole), or a sum that cancels on every row (simplified.h): rounding, not a
  // formula. Such formulas stay in the populations (their offspring may be sound) but not in the
  // front.
  bool cancels(const Genome& g) const {
    return std::any_of(g.begin(), g.end(), [&](const Node& n) {
      return n.op == Op::constant && std::abs(n.value) > largest_constant;
    }) || relies_on_cancellation(g, train);
  }
};

// Constants may reach 1e6 times the largest magnitude in the data (or 1e6 for data within ±1).
double constant_limit(const Data& data) {
  double scale = 1;
  for (double y : data.target) scale = std::max(scale, std::abs(y));
  for (const auto& column : data.columns)
    for (double x : column) scale = std::max(scale, std::abs(x));
  return 1e6 * scale;
}

// Options::starts read over the data's variables.
std::vector<Genome> starting_formulas(const Data& data, const Options& o) {
  if (o.starts.size() > OptionRanges::starts)
    throw InvalidField("starts", fmt::format("{} start formulas; at most {}", o.starts.size(), OptionRanges::starts));
  std::vector<Genome> out;
  for (std::size_t k = 0; k < o.starts.size(); ++k) {
    try {
      const expr::Expression e = expr::parse(o.starts[k], data.variables);
      Genome g(e.nodes().begin(), e.nodes().end());
      if (o.weights.of(g) > o.max_size)
        throw InvalidArgument(fmt::format("size {} is over max_size {}", o.weights.of(g), o.max_size));
      if (std::count_if(g.begin(), g.end(), is_free_constant) > static_cast<std::ptrdiff_t>(kMaxConstants))
        throw InvalidArgument(fmt::format("more than {} constants", kMaxConstants));
      out.push_back(std::move(g));
    } catch (const std::exception& e) {
      throw InvalidField("starts", fmt::format("start formula {} '{}': {}", k + 1, o.starts[k], e.what()));
    }
  }
  return out;
}

void validate(const Data& data, const Options& o) {
  if (data.variables.empty()) throw InvalidArgument("no variables to fit with");
  expr::Expression({{Op::variable, 0, 0}}, data.variables);  // names must be identifiers, distinct
  if (data.columns.size() != data.variables.size())
    throw InvalidArgument("each variable needs one column of values");
  if (data.target.empty()) throw InvalidArgument("no data rows");
  for (std::size_t v = 0; v < data.columns.size(); ++v) {
    if (data.columns[v].size() != data.target.size())
      throw InvalidArgument(fmt::format("column '{}' has {} rows, the target {}", data.variables[v],
                                        data.columns[v].size(), data.target.size()));
    for (std::size_t r = 0; r < data.target.size(); ++r)
      if (!std::isfinite(data.columns[v][r]))
        throw InvalidArgument(fmt::format("column '{}' row {} is not a finite number",
                                          data.variables[v], r + 1));
  }
  for (std::size_t r = 0; r < data.target.size(); ++r)
    if (!std::isfinite(data.target[r]))
      throw InvalidArgument(fmt::format("target row {} is not a finite number", r + 1));
  if (o.metric == Metric::mean_relative || o.metric == Metric::max_rel)
    for (std::size_t r = 0; r < data.target.size(); ++r)
      if (data.target[r] == 0)
        throw InvalidArgument(fmt::format("the {} error needs a non-zero target, but row {} is 0",
                                          metric_name(o.metric), r + 1));
  using R = OptionRanges;
  const auto in_range = [](auto value, auto lo, auto hi, std::string_view key) {
    if (!(value >= lo && value <= hi))
      throw InvalidField(std::string(key), fmt::format("{} must be in [{}, {}], got {}", key, lo, hi, value));
  };
  in_range(o.max_size, 1, R::max_size, "max_size");
  in_range(o.enumerate_max_size, 0, R::enumerate_size, "enumerate_size");
  in_range(o.islands, 1, R::islands, "islands");
  in_range(o.population, 4, R::population, "population");
  in_range(o.threads, 0, R::threads, "threads");
  if (!(o.enumerate_limit >= 0 && o.enumerate_limit <= R::enumerate_limit))
    throw InvalidArgument(fmt::format("the enumeration limit must be in [0, {}], got {}", R::enumerate_limit,
                                      o.enumerate_limit));
  if (o.snap_tolerance && !(*o.snap_tolerance > 0 && *o.snap_tolerance <= R::snap_tolerance))
    throw InvalidField("snap_tolerance", fmt::format("snap_tolerance must be in (0, 1], got {}", *o.snap_tolerance));
  if (data.target.size() > R::rows)
    throw InvalidArgument(fmt::format("{} data rows; at most {}", data.target.size(), R::rows));
  if (o.max_generations.value_or(0) < 0 || o.max_evaluations.value_or(0) < 0)
    throw InvalidArgument("the generation and evaluation budgets must be ≥ 0");
  if (!(o.choose_factor >= 1)) throw InvalidArgument("the choose factor must be ≥ 1");
  if (!(o.test_fraction >= 0 && o.test_fraction < 1))
    throw InvalidArgument("the test fraction must be in [0, 1)");
  if (!(o.time_limit_s > 0 && o.time_limit_s <= R::time_s))
    throw InvalidArgument(fmt::format("the time limit must be in (0, {:g}] seconds", R::time_s));
  if (o.target_error && !(*o.target_error >= 0))
    throw InvalidArgument("the target error must be a number ≥ 0");
}

std::vector<std::size_t> test_rows(std::size_t rows, const Options& o) {
  const auto count = static_cast<std::size_t>(std::ceil(o.test_fraction * static_cast<double>(rows)));
  if (count == 0) return {};
  if (count >= rows) throw InvalidArgument("the test fraction leaves no rows to train on");
  std::vector<std::size_t> order(rows);
  std::iota(order.begin(), order.end(), 0);
  if (o.split == Split::random) std::shuffle(order.begin(), order.end(), Rng(o.seed ^ 0x5eed5eedULL));
  std::vector<std::size_t> test(order.end() - static_cast<std::ptrdiff_t>(count), order.end());
  std::sort(test.begin(), test.end());
  return test;
}

Problem make_problem(const Data& data, const Options& o) {
  Problem p{{}, {}, {}, {}, {}, o.metric, o.constants, o.weights, constant_limit(data), {}};
  const auto test = test_rows(data.target.size(), o);
  std::vector<bool> held_out(data.target.size(), false);
  for (auto r : test) held_out[r] = true;
  p.train_columns.resize(data.columns.size());
  p.test_columns.resize(data.columns.size());
  for (std::size_t r = 0; r < data.target.size(); ++r) {
    for (std::size_t v = 0; v < data.columns.size(); ++v)
      (held_out[r] ? p.test_columns : p.train_columns)[v].push_back(data.columns[v][r]);
    (held_out[r] ? p.test_target : p.train_target).push_back(data.target[r]);
  }
  for (const auto& c : p.train_columns) p.train.columns.emplace_back(c);
  p.train.target = p.train_target;
  const std::vector<std::span<const double>> all_rows(data.columns.begin(), data.columns.end());
  p.rules = {o.operators, o.constants, o.weights, positive_columns(all_rows)};
  if (o.metric == Metric::mean_relative || o.metric == Metric::max_rel)
    for (double y : p.train_target) p.train.weights.push_back(y != 0 ? 1 / (y * y) : 1.0);
  return p;
}

// The best formula found of each size.
class Archive {
 public:
  static constexpr double kLowerBy = 1e-6;

  // Differences in loss below `noise` are rounding, not improvement.
  explicit Archive(double noise) : noise_(noise) {}

  void offer(const Individual& x) {
    if (!std::isfinite(x.loss) || x.cancels) return;
    auto [it, inserted] = best_.try_emplace(x.size, x);
    if (!inserted && x.loss < it->second.loss) it->second = x;
  }
  // x takes its size's place unless the formula there is more accurate by more than the
  // tolerance (a snapped form over the unsnapped one it came from, whose error it nearly keeps).
  void offer_within(const Individual& x, double tolerance, double floor) {
    if (!std::isfinite(x.loss) || x.cancels) return;
    const auto it = best_.find(x.size);
    if (it == best_.end() || x.loss <= it->second.loss * (1 + tolerance) + floor) best_.insert_or_assign(x.size, x);
  }
  // Each size's best that beats the smaller ones by more than rounding, by 10⁻⁶ of its error and
  // by `noise`: as fitted, or as printed (Individual::ranking()) — an exact polynomial over its
  // factored form, whose printed roots are not exact; a fit finer than 6 digits print still shows.
  // (A bigger formula whose error is lower by 10⁻⁹ of it gets there by rounding:
  // 1105270 − 0.197243·(5603590 − n) for 0.197243·n + 0.250673.)
  std::vector<const Individual*> front() const {
    std::vector<const Individual*> out;
    for (const auto& [size, x] : best_)
      if (out.empty() || lower(x.loss, out.back()->loss) || lower(x.ranking(), out.back()->ranking())) out.push_back(&x);
    return out;
  }

 private:
  bool lower(double a, double b) const { return a < b * (1 - kLowerBy) - noise_; }

  double noise_;
  std::map<int, Individual> best_;
};

// The loss that double rounding alone can make: 1e-13 of the target's scale.
double rounding_noise(const Problem& p) {
  if (p.metric == Metric::mean_relative || p.metric == Metric::max_rel || p.metric == Metric::r2) return 1e-13;
  double mean_square = 0;
  for (double y : p.train_target) mean_square += y * y / static_cast<double>(p.train_target.size());
  return 1e-13 * std::sqrt(mean_square);
}

// Exhaustive enumeration: every distinct form (canonical key) of each size, smallest first,
// until the size or count limit. Constants start at 1.
std::vector<Genome> enumerate_forms(const Alphabet& a, const Options& o) {
  std::vector<std::vector<Genome>> by_size(static_cast<std::size_t>(o.enumerate_max_size) + 1);
  std::vector<Genome> all;
  std::unordered_set<std::string> seen;
  const auto limit = static_cast<std::size_t>(o.enumerate_limit);
  const auto full = [&] { return all.size() >= limit; };
  const auto add = [&](Genome g, int size) {
    if (full() || !seen.insert(canonical_key(g)).second) return;
    by_size[static_cast<std::size_t>(size)].push_back(g);
    all.push_back(std::move(g));
  };
  const auto join = [](const Genome& x, const Genome* y, Op op) {
    Genome g = x;
    if (y) g.insert(g.end(), y->begin(), y->end());
    g.push_back({op, 0, 0});
    return g;
  };
  for (int size = 1; size <= std::min(o.enumerate_max_size, o.max_size) && !full(); ++size) {
    if (size == a.weights.of(Op::variable))
      for (std::uint32_t v = 0; v < a.variables; ++v) add({{Op::variable, v, 0}}, size);
    if (size == a.weights.of(Op::constant) && a.constants != Constants::none)
      add({{Op::constant, 0, 1.0}}, size);
    for (Op op : a.unary) {
      const int rest = size - a.weights.of(op);
      if (rest >= 1)
        for (const auto& x : by_size[static_cast<std::size_t>(rest)]) {
          if (full()) break;
          add(join(x, nullptr, op), size);
        }
    }
    for (Op op : a.binary)
      for (int left = 1; left < size - a.weights.of(op) && !full(); ++left) {
        const int right = size - a.weights.of(op) - left;
        for (const auto& x : by_size[static_cast<std::size_t>(left)])
          for (const auto& y : by_size[static_cast<std::size_t>(right)]) {
            if (full()) break;
            add(join(x, &y, op), size);
          }
      }
  }
  return all;
}

// Fits an enumerated form from two starting points when it has nonlinear constants.
Individual fit_form(const Problem& p, const Genome& form) {
  const std::string key = canonical_key(form);
  Individual best = p.evaluate(form, key);
  const auto linear = linear_constants(form);
  if (std::find(linear.begin(), linear.end(), false) != linear.end()) {
    Genome other = form;
    for (auto& n : other)
      if (is_free_constant(n)) n.value = -0.5;
    Individual second = p.evaluate(other, key);
    if (better(second, best)) best = std::move(second);
  }
  return best;
}

// Pareto rank by (loss, size): 0 for the non-dominated, 1 for the next layer, and so on.
std::vector<int> pareto_ranks(const std::vector<Individual>& xs) {
  std::vector<std::size_t> order(xs.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto i, auto j) {
    return xs[i].size < xs[j].size || (xs[i].size == xs[j].size && xs[i].loss < xs[j].loss);
  });
  std::vector<int> rank(xs.size(), -1);
  std::vector<double> best_loss;  // best_loss[r]: lowest loss seen so far in layer r
  for (std::size_t i : order) {
    int r = 0;
    while (r < static_cast<int>(best_loss.size()) && !(xs[i].loss < best_loss[static_cast<std::size_t>(r)])) ++r;
    if (r == static_cast<int>(best_loss.size())) best_loss.push_back(INFINITY);
    best_loss[static_cast<std::size_t>(r)] = xs[i].loss;
    rank[i] = r;
  }
  return rank;
}

// Indices of xs by Pareto rank, then error (then size); ties keep their order.
std::vector<std::size_t> pareto_order(const std::vector<Individual>& xs, const std::vector<int>& ranks) {
  std::vector<std::size_t> order(xs.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](auto i, auto j) {
    return ranks[i] < ranks[j] || (ranks[i] == ranks[j] && better(xs[i], xs[j]));
  });
  return order;
}

// The budgets every loop of the search looks at: the time limit (and the calling thread's
// deadline), the cancel flags, a process-wide stop request. Thread-safe: islands poll it.
class Budget {
 public:
  explicit Budget(const Options& o) : options_(o), limit_(current_limit()) {}

  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  bool cancelled() const {
    return (options_.cancel && options_.cancel->load()) || (limit_.cancel && limit_.cancel->load());
  }
  bool out_of_time() const {
    return seconds() >= options_.time_limit_s || std::chrono::steady_clock::now() >= limit_.deadline;
  }
  bool expired() const { return stop_requested() || cancelled() || out_of_time(); }

 private:
  const Options& options_;
  const WorkLimit limit_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Random formulas tried per population slot before the formula space counts as exhausted (it can
// be smaller than the population: one variable, "+" and size 1 make few distinct formulas).
constexpr std::size_t kAttemptsPerSlot = 20;

class Island {
 public:
  Island(const Problem& p, const Alphabet& a, const Options& o, const Budget& budget, std::uint64_t stream)
      : problem_(p), alphabet_(a), options_(o), budget_(budget), rng_(o.seed * 0x9E3779B97F4A7C15ULL + stream),
        cache_limit_(std::min<std::size_t>(200'000, 800'000 / static_cast<std::size_t>(o.islands))) {}

  void populate(const std::vector<Individual>& seeds) {
    for (const auto& s : seeds) admit(s);
    const auto wanted = static_cast<std::size_t>(options_.population);
    for (std::size_t attempt = 0; population_.size() < wanted && attempt < kAttemptsPerSlot * wanted; ++attempt) {
      if (budget_.expired()) break;
      const int size = std::uniform_int_distribution<int>(1, std::min(alphabet_.max_size, 15))(rng_);
      admit(evaluate(alphabet_.random_tree(rng_, size)));
    }
    select();
  }

  void generation() {
    std::vector<Individual> children;
    for (std::size_t i = 0; i < population_.size(); ++i) {
      if (budget_.expired()) break;
      Genome child;
      if (std::uniform_real_distribution<double>(0, 1)(rng_) < 0.5) {
        const Genome& mother = tournament().genome;
        child = crossover(mother, tournament().genome, alphabet_, rng_);
      } else {
        child = mutate(tournament().genome, alphabet_, rng_);
      }
      children.push_back(evaluate(std::move(child)));
    }
    for (auto& child : children) admit(std::move(child));
    select();
  }

  // Starts afresh from `seeds` and new random formulas (the cache stays).
  void restart(const std::vector<Individual>& seeds) {
    population_.clear();
    rank_.clear();
    present_.clear();
    populate(seeds);
  }

  double best_loss() const {
    double best = INFINITY;
    for (const auto& x : population_) best = std::min(best, x.loss);
    return best;
  }

  const std::vector<Individual>& population() const { return population_; }
  std::int64_t evaluations() const { return evaluations_; }

  // The best few, for the next island.
  std::vector<Individual> emigrants(std::size_t count) const {
    std::vector<Individual> sorted = population_;
    std::sort(sorted.begin(), sorted.end(), better);
    sorted.resize(std::min(count, sorted.size()));
    return sorted;
  }
  void immigrate(const std::vector<Individual>& xs) {
    for (const auto& x : xs) admit(x);
    select();
  }

 private:
  Individual evaluate(const Genome& g) {
    const std::string key = canonical_key(g);
    if (const auto it = cache_.find(key); it != cache_.end()) return it->second;
    ++evaluations_;
    Individual x = problem_.evaluate(g, key);
    if (cache_.size() > cache_limit_) cache_.clear();
    cache_.emplace(key, x);
    return x;
  }

  void admit(Individual x) {
    if (present_.insert(x.key).second) population_.push_back(std::move(x));
  }

  const Individual& tournament() {
    std::uniform_int_distribution<std::size_t> any(0, population_.size() - 1);
    const std::size_t a = any(rng_), b = any(rng_);
    return rank_[a] < rank_[b] || (rank_[a] == rank_[b] && better(population_[a], population_[b]))
               ? population_[a]
               : population_[b];
  }

  // Keeps the best `population` formulas by Pareto rank, then error.
  void select() {
    const auto ranks = pareto_ranks(population_);
    auto order = pareto_order(population_, ranks);
    order.resize(std::min(order.size(), static_cast<std::size_t>(options_.population)));
    std::vector<Individual> kept;
    rank_.clear();
    present_.clear();
    for (auto i : order) {
      rank_.push_back(ranks[i]);
      present_.insert(population_[i].key);
      kept.push_back(std::move(population_[i]));
    }
    population_ = std::move(kept);
  }

  const Problem& problem_;
  const Alphabet& alphabet_;
  const Options& options_;
  const Budget& budget_;
  Rng rng_;
  std::size_t cache_limit_;  // memoized formulas, ≤ 800k over all islands
  std::vector<Individual> population_;
  std::vector<int> rank_;
  std::unordered_set<std::string> present_;
  std::unordered_map<std::string, Individual> cache_;
  std::int64_t evaluations_ = 0;
};

constexpr int kEpochGenerations = 5;
// Every this many epochs the island with the worst best error starts afresh (with two islands or
// more; the archive keeps what it found). A search that goes wrong goes wrong early, into towers
// of fitted constants that improve slowly and never leave; one that goes right finds its formula
// in tens of generations.
constexpr int kRestartEpochs = 20;
constexpr std::size_t kMigrants = 5;
constexpr std::size_t kEnumerationChunk = 512;

/// The metric of `formula` on the test rows where there are some, else on the training rows.
double held_out_error(const expr::Expression& formula, const Problem& p) {
  const bool test = !p.test_target.empty();
  const auto& columns = test ? p.test_columns : p.train_columns;
  const std::vector<std::span<const double>> spans(columns.begin(), columns.end());
  std::vector<double> predicted(test ? p.test_target.size() : p.train_target.size());
  expr::evaluate_batch(formula, spans, predicted);
  return measure(p.metric, predicted, test ? p.test_target : p.train_target);
}

Candidate candidate(const Individual& x, const Problem& p, const Data& data) {
  Candidate c{expr::Expression(x.genome, data.variables), x.size,
              p.metric == Metric::r2 ? 1 - x.loss : x.loss, std::nullopt};
  if (!p.test_target.empty()) c.test_error = held_out_error(c.formula, p);
  c.printed_error = held_out_error(rounded(c.formula, kPrintedDigits), p);
  return c;
}

// Seeds for each island: the enumeration's Pareto layers dealt out round-robin, best first.
std::vector<std::vector<Individual>> seeds_for(const std::vector<Individual>& fitted,
                                               std::size_t islands, std::size_t count) {
  std::vector<Individual> finite;
  for (const auto& x : fitted)
    if (std::isfinite(x.loss)) finite.push_back(x);
  const auto order = pareto_order(finite, pareto_ranks(finite));
  std::vector<std::vector<Individual>> seeds(islands);
  for (std::size_t k = 0; k < order.size() && k < count * islands; ++k)
    seeds[k % islands].push_back(finite[order[k]]);
  return seeds;
}

class Search {
 public:
  Search(const Data& data, const Options& o, const std::function<void(const Progress&)>& progress)
      : data_(data),
        options_(o),
        progress_(progress),
        problem_(make_problem(data, o)),
        alphabet_(o, static_cast<std::uint32_t>(data.variables.size())),
        arena_(std::min(o.threads > 0 ? o.threads : 1 << 20, oneapi::tbb::info::default_concurrency())),
        budget_(o),
        archive_(rounding_noise(problem_)),
        starts_(starting_formulas(data, o)) {}

  Result run() {
    auto fitted = enumerate();
    for (const Genome& g : starts_) {
      fitted.push_back(problem_.evaluate(g, canonical_key(g)));
      archive_.offer(fitted.back());
      ++evaluations_;
    }
    // The front only, not the populations: a smooth function on a short interval can pass for a
    // polynomial (sin on [−1, 1] at 20 points, to 10⁻¹² at degree 9), which must not steer the
    // genetic search.
    if (options_.transformed_polynomials && problem_.constants != Constants::none)
      for (const Genome& g : transformed_polynomials(problem_.train, problem_.rules.operators, problem_.weights))
        if (alphabet_.fits(g)) {
          archive_.offer(problem_.evaluate(g, canonical_key(g)));
          ++evaluations_;
        }
    if (!stopped()) check_budget(false);  // e.g. a cancel asked for by the last report
    if (options_.max_generations == 0) stopped_by_ = StopReason::generations;
    if (!stopped()) evolve(fitted);
    Result result;
    const std::vector<Individual> front = options_.snap ? snapped_front() : copied(archive_.front());
    for (const Individual& x : front) result.front.push_back(candidate(x, problem_, data_));
    if (result.front.empty())
      throw InvalidArgument(stopped_by_ == StopReason::cancelled || stopped_by_ == StopReason::time
                                ? fmt::format("the search stopped ({}) before any formula was evaluated",
                                              to_string(*stopped_by_))
                                : std::string("no formula could be evaluated on these data"));
    double best_loss = INFINITY;
    for (const Candidate& c : result.front)
      best_loss = std::min(best_loss, to_loss(options_.metric, c.test_error.value_or(c.train_error)));
    result.chosen = choose(result.front, options_.metric, options_.choice, options_.choose_factor,
                           noise_floor(data_.target, options_.metric, best_loss));
    result.evaluations = evaluations_;
    result.generations = generations_;
    result.seconds = budget_.seconds();
    result.stopped_by = *stopped_by_;
    return result;
  }

 private:
  static std::vector<Individual> copied(const std::vector<const Individual*>& xs) {
    std::vector<Individual> out;
    for (const Individual* x : xs) out.push_back(*x);
    return out;
  }

  // The front with each formula's constants snapped (snap.h) and simplified again: an exact
  // constant of 0 drops its term. Snapping moves errors a little, so the front is taken anew.
  std::vector<Individual> snapped_front() {
    SnapSettings settings;
    settings.metric = options_.metric;
    settings.constants = options_.constants;
    settings.tolerance = options_.snap_tolerance.value_or(free_snap_tolerance(options_.metric, problem_.train.size()));
    settings.floor = std::max(rounding_noise(problem_),
                              options_.target_error ? to_loss(options_.metric, *options_.target_error) : 0.0);
    settings.stop = [this] { return stop_requested() != 0 || budget_.cancelled(); };
    settings.acceptable = [this](const Genome& g) { return !problem_.cancels(g); };
    // Each refit fits every training row: a few hundred per formula for small data, fewer for large.
    settings.max_refits = static_cast<int>(std::clamp<std::size_t>(20'000'000 / (problem_.train.size() + 1), 20, 500));
    const std::vector<const Individual*> unsnapped = archive_.front();
    Archive snapped_archive(rounding_noise(problem_));
    for (const Individual* x : unsnapped) snapped_archive.offer(as_printed(*x));
    for (const Individual* x : unsnapped) {
      const Individual y = simplified_snap(snapped(x->genome, problem_.train, settings), settings);
      snapped_archive.offer_within(y, settings.tolerance, settings.floor);
      if (auto polynomial = expanded(y, x->loss, settings)) snapped_archive.offer_within(*polynomial, settings.tolerance, settings.floor);
    }
    return copied(snapped_archive.front());
  }

  // A snapped formula simplified again (an exact 0 drops its term), as the front ranks it.
  // Where the simplification changes it, the simplified formula is snapped once more: merging
  // constants can make a free scale (x/(x/3 − 10/3) − 3 became 10/(x/3 − 10/3), whose scale held
  // at 1 reads 30/(x − 10)).
  Individual simplified_snap(Snapped s, const SnapSettings& settings) const {
    if (auto simple = simplified_on_rows(s.genome)) {
      s = snapped(with_free_coefficients(std::move(*simple)), problem_.train, settings);
      if (auto again = simplified_on_rows(s.genome)) s.genome = std::move(*again);
    }
    Individual y{s.genome, canonical_key(s.genome), s.loss, problem_.weights.of(s.genome)};
    y.cancels = problem_.cancels(y.genome);
    return as_printed(std::move(y));
  }

  // g with its exact rationals freed (at their values) but for exponents: snapping decides anew
  // (a free scale among them is held at 1 again). Multiples of π and the like stay.
  static Genome with_free_coefficients(Genome g) {
    for (std::size_t i = 0; i < g.size(); ++i) {
      const bool exponent = i + 1 < g.size() && g[i + 1].op == Op::pow;
      if (expr::is_exact(g[i]) && g[i].symbol == expr::Symbol::one && !exponent) g[i] = expr::Node{Op::constant, 0, g[i].value};
    }
    return g;
  }

  std::optional<Genome> simplified_on_rows(const Genome& g) const {
    std::vector<double> values(problem_.train.size());
    expr::evaluate_batch(expr::Expression(g, data_.variables), problem_.train.columns, values);
    return simplified(g, values, problem_.train, problem_.rules);
  }

  // x with its printed loss: its constants rounded to kPrintedDigits, on the training rows.
  Individual as_printed(Individual x) const {
    const expr::Expression printed = rounded(expr::Expression(x.genome, data_.variables), kPrintedDigits);
    std::vector<double> values(problem_.train.size());
    expr::evaluate_batch(printed, problem_.train.columns, values);
    x.printed_loss = to_loss(options_.metric, measure(options_.metric, values, problem_.train_target));
    if (std::isnan(x.printed_loss)) x.printed_loss = INFINITY;
    return x;
  }

  // A polynomial of the front multiplied out (expanded.h), its coefficients fitted and snapped:
  // where they are simple, its printed form is exact and the factored one's is not. Only where
  // the operators write it, its monomials are at most half the rows (never an interpolation), and
  // it fits as well as x did before its snap (`loss`).
  std::optional<Individual> expanded(const Individual& x, double loss, const SnapSettings& settings) const {
    constexpr std::size_t kMostMonomials = 16;
    const auto writes = [this](Op op) { return std::ranges::find(problem_.rules.operators, op) != problem_.rules.operators.end(); };
    if (!writes(Op::add) || !writes(Op::mul) || !writes(Op::pow)) return std::nullopt;
    const std::optional<int> degree = polynomial_degree(x.genome);
    const auto variables = static_cast<std::uint32_t>(data_.columns.size());
    if (!degree || *degree < 2 ||
        monomial_count(*degree, variables) > std::min(kMostMonomials, problem_.train.size() / 2))
      return std::nullopt;
    const Snapped fitted = refitted(dense_polynomial(*degree, variables), problem_.train, settings);
    if (!(fitted.loss <= loss * (1 + settings.tolerance) + settings.floor)) return std::nullopt;
    Individual y = simplified_snap(snapped(fitted.genome, problem_.train, settings), settings);
    if (y.size > options_.max_size) return std::nullopt;
    return y;
  }

  std::vector<Individual> enumerate() {
    const auto forms = enumerate_forms(alphabet_, options_);
    std::vector<Individual> fitted(forms.size());
    for (std::size_t first = 0; first < forms.size() && !stopped(); first += kEnumerationChunk) {
      const std::size_t last = std::min(forms.size(), first + kEnumerationChunk);
      // The first chunk is always fitted whole, so that even a search stopped at once has a
      // front to report; later chunks stop at the budget form by form.
      const bool first_chunk = first == 0;
      arena_.execute([&] {
        oneapi::tbb::parallel_for(first, last, [&](std::size_t i) {
          if (first_chunk || !budget_.expired()) fitted[i] = fit_form(problem_, forms[i]);
        });
      });
      for (std::size_t i = first; i < last; ++i) archive_.offer(fitted[i]);
      evaluations_ += std::count_if(fitted.begin() + static_cast<std::ptrdiff_t>(first),
                                    fitted.begin() + static_cast<std::ptrdiff_t>(last),
                                    [](const Individual& x) { return !x.genome.empty(); });
      check_budget(false);
      report();
    }
    if (forms.empty()) report();
    return fitted;
  }

  void evolve(const std::vector<Individual>& fitted) {
    const auto count = static_cast<std::size_t>(options_.islands);
    std::vector<Island> islands;
    for (std::size_t i = 0; i < count; ++i) islands.emplace_back(problem_, alphabet_, options_, budget_, i + 1);
    const std::int64_t enumerated = evaluations_;
    const auto seeds = seeds_for(fitted, count, static_cast<std::size_t>(options_.population) / 2);
    in_parallel(islands, [&](Island& island, std::size_t i) {
      island.populate(seeds[i]);
    });
    collect(islands, enumerated);
    check_budget(false);
    int epochs_since_restart = 0;
    while (!stopped()) {
      const int epoch = options_.max_generations
                            ? static_cast<int>(std::min<std::int64_t>(
                                  kEpochGenerations, *options_.max_generations - generations_))
                            : kEpochGenerations;
      in_parallel(islands, [&](Island& island, std::size_t) {
        for (int g = 0; g < epoch; ++g) island.generation();
      });
      generations_ += epoch;
      collect(islands, enumerated);
      migrate(islands);
      if (islands.size() > 1 && ++epochs_since_restart == kRestartEpochs) {
        epochs_since_restart = 0;
        const auto worst = std::max_element(islands.begin(), islands.end(), [](const Island& a, const Island& b) {
          return a.best_loss() < b.best_loss();
        });
        worst->restart(seeds[static_cast<std::size_t>(worst - islands.begin())]);
      }
      check_budget(true);
      report();
    }
  }

  // The islands' formulas into the archive, their evaluations into the count.
  void collect(const std::vector<Island>& islands, std::int64_t enumerated) {
    evaluations_ = enumerated;
    for (const auto& island : islands) {
      evaluations_ += island.evaluations();
      for (const auto& x : island.population()) archive_.offer(x);
    }
  }

  void in_parallel(std::vector<Island>& islands, const auto& work) {
    arena_.execute([&] {
      oneapi::tbb::parallel_for(std::size_t{0}, islands.size(),
                                [&](std::size_t i) { work(islands[i], i); });
    });
  }

  static void migrate(std::vector<Island>& islands) {
    if (islands.size() < 2) return;
    std::vector<std::vector<Individual>> leaving;
    for (const auto& island : islands) leaving.push_back(island.emigrants(kMigrants));
    for (std::size_t i = 0; i < islands.size(); ++i)
      islands[i].immigrate(leaving[(i + islands.size() - 1) % islands.size()]);
  }

  // The generation budget applies to the genetic search only.
  void check_budget(bool evolving) {
    if (const int signal = stop_requested()) throw Interrupted(Interrupted::Reason::signal, signal);
    const auto front = archive_.front();
    if (budget_.cancelled())
      stopped_by_ = StopReason::cancelled;
    else if (options_.target_error && !front.empty() &&
        front.back()->loss <= to_loss(options_.metric, *options_.target_error))
      stopped_by_ = StopReason::target_error;
    else if (options_.max_evaluations && evaluations_ >= *options_.max_evaluations)
      stopped_by_ = StopReason::evaluations;
    else if (options_.max_generations && generations_ >= *options_.max_generations && evolving)
      stopped_by_ = StopReason::generations;
    else if (budget_.out_of_time())
      stopped_by_ = StopReason::time;
  }

  bool stopped() const { return stopped_by_.has_value(); }

  void report() {
    if (!progress_) return;
    std::vector<Candidate> front;
    for (const Individual* x : archive_.front()) front.push_back(candidate(*x, problem_, data_));
    const double elapsed = budget_.seconds();
    progress_(Progress{elapsed, std::max(0.0, options_.time_limit_s - elapsed), evaluations_,
                       generations_, &front});
  }

  const Data& data_;
  const Options& options_;
  const std::function<void(const Progress&)>& progress_;
  const Problem problem_;
  const Alphabet alphabet_;
  oneapi::tbb::task_arena arena_;
  Budget budget_;
  Archive archive_;
  const std::vector<Genome> starts_;  // Options::starts, read (and refused) before any work
  std::int64_t evaluations_ = 0, generations_ = 0;
  std::optional<StopReason> stopped_by_;
};

}  // namespace

double free_snap_tolerance(Metric metric, std::size_t rows) {
  if (metric == Metric::max_abs || metric == Metric::max_rel) return 1e-4;
  return std::min(1e-3, 1.0 / static_cast<double>(std::max<std::size_t>(rows, 1)));
}

Result search(const Data& data, const Options& options,
              const std::function<void(const Progress&)>& on_progress) {
  validate(data, options);
  return Search(data, options, on_progress).run();
}

}  // namespace specula::fit
