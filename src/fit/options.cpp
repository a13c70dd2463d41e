// Parsing of the search's options, the error metrics, and the choice of a formula from a front.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <numeric>
#include <span>

#include "genome.h"
#include "specula/fit/fit.h"
#include "specula/io/values.h"

namespace specula::fit {

using expr::Op;

namespace {

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  while (true) {
    const auto end = text.find(separator);
    std::string_view part = text.substr(0, end);
    while (!part.empty() && part.front() == ' ') part.remove_prefix(1);
    while (!part.empty() && part.back() == ' ') part.remove_suffix(1);
    parts.push_back(part);
    if (end == std::string_view::npos) return parts;
    text.remove_prefix(end + 1);
  }
}

// The names of the option values: one switch per enum, every enumerator in it, "" outside the enum
// (what names_complete checks). Parsing, messages and metric_name() & co. all read these.
constexpr std::string_view name_of(Metric metric) noexcept {
  switch (metric) {
    case Metric::rms: return "rms";
    case Metric::mae: return "mae";
    case Metric::max_abs: return "max-abs";
    case Metric::max_rel: return "max-rel";
    case Metric::mean_relative: return "mean-relative";
    case Metric::r2: return "r2";
  }
  return "";
}
static_assert(names_complete<Metric, kMetricCount>([](Metric m) { return name_of(m); }));

constexpr std::string_view name_of(Constants constants) noexcept {
  switch (constants) {
    case Constants::fitted: return "fitted";
    case Constants::integer: return "integer";
    case Constants::none: return "none";
  }
  return "";
}
static_assert(names_complete<Constants, kConstantsCount>([](Constants c) { return name_of(c); }));

constexpr std::string_view name_of(Split split) noexcept {
  switch (split) {
    case Split::random: return "random";
    case Split::last: return "last";
  }
  return "";
}
static_assert(names_complete<Split, kSplitCount>([](Split s) { return name_of(s); }));

constexpr std::string_view name_of(Choice choice) noexcept {
  switch (choice) {
    case Choice::parsimonious: return "parsimonious";
    case Choice::knee: return "knee";
    case Choice::best: return "best";
  }
  return "";
}
static_assert(names_complete<Choice, kChoiceCount>([](Choice c) { return name_of(c); }));

constexpr std::string_view name_of(StopReason reason) noexcept {
  switch (reason) {
    case StopReason::time: return "time";
    case StopReason::generations: return "generations";
    case StopReason::evaluations: return "evaluations";
    case StopReason::target_error: return "target error";
    case StopReason::cancelled: return "cancelled";
  }
  return "";
}
static_assert(names_complete<StopReason, kStopReasonCount>([](StopReason r) { return name_of(r); }));

/// The value of E named `name`, or InvalidArgument "unknown WHAT 'name' (expected a, b or c)".
template <class E, std::size_t count>
E parse_named(std::string_view name, std::string_view what) {
  const auto name_of_e = [](E e) { return name_of(e); };
  if (const auto value = enum_named<E, count>(name, name_of_e)) return *value;
  throw InvalidArgument(
      fmt::format("unknown {} '{}' (expected {})", what, name, names_listed<E, count>(name_of_e)));
}

std::optional<Op> operator_named(std::string_view name) {
  for (std::size_t i = 0; i < expr::kOpCount; ++i) {
    const auto op = static_cast<Op>(i);
    if (expr::arity(op) > 0 && operator_symbol(op) == name) return op;
  }
  return expr::function_named(name);  // "pow" as well as "^"
}

}  // namespace

Metric parse_metric(std::string_view name) { return parse_named<Metric, kMetricCount>(name, "metric"); }
std::string_view metric_name(Metric metric) { return name_of(metric); }

Constants parse_constants(std::string_view name) {
  return parse_named<Constants, kConstantsCount>(name, "constants mode");
}
std::string_view constants_name(Constants constants) { return name_of(constants); }

std::optional<Split> split_named(std::string_view name) {
  return enum_named<Split, kSplitCount>(name, [](Split s) { return name_of(s); });
}
std::string_view split_name(Split split) { return name_of(split); }

Choice parse_choice(std::string_view name) { return parse_named<Choice, kChoiceCount>(name, "choice"); }
std::string_view choice_name(Choice choice) { return name_of(choice); }

std::string_view to_string(StopReason reason) { return name_of(reason); }

double to_loss(Metric metric, double error) { return metric == Metric::r2 ? 1 - error : error; }

namespace {

// |f − y|/|y|; 0 where f = y = 0, inf where only y is 0.
double relative(double error, double y) { return error == 0 ? 0 : error / std::abs(y); }

}  // namespace

double measure(Metric metric, std::span<const double> predicted, std::span<const double> target) {
  const auto n = static_cast<double>(target.size());
  double sum = 0, largest = 0;
  for (std::size_t i = 0; i < target.size(); ++i) {
    const double e = std::abs(predicted[i] - target[i]);
    if (!std::isfinite(e)) return INFINITY;
    largest = std::max(largest, metric == Metric::max_rel ? relative(e, target[i]) : e);
    sum += metric == Metric::mae             ? e
           : metric == Metric::mean_relative ? e / std::abs(target[i])
                                             : e * e;
  }
  switch (metric) {
    case Metric::rms: return std::sqrt(sum / n);
    case Metric::mae:
    case Metric::mean_relative: return sum / n;
    case Metric::max_abs:
    case Metric::max_rel: return largest;
    case Metric::r2: {
      const double mean = std::accumulate(target.begin(), target.end(), 0.0) / n;
      double total = 0;
      for (double y : target) total += (y - mean) * (y - mean);
      return total > 0 ? 1 - sum / total : (sum == 0 ? 1.0 : -INFINITY);
    }
  }
  unreachable();
}

SizeWeights::SizeWeights() { weight_.fill(1); }

/// An elementary constant (an op over exact constants only: exp(−1/2), (2π)^(−1/2)) is a constant:
/// it counts as one leaf, as a snapped 3π/4 does.
int SizeWeights::of(std::span<const expr::Node> nodes) const {
  const std::vector<bool> exact = expr::exact_only_subtrees(nodes);
  const std::vector<std::size_t> starts = subtree_starts(nodes);
  int size = 0;
  for (std::size_t i = nodes.size(); i-- > 0;) {
    if (exact[i] && expr::arity(nodes[i].op) > 0) {  // the whole elementary constant: one leaf
      size += of(Op::constant);
      i = starts[i];
      continue;
    }
    size += of(nodes[i].op);
  }
  return size;
}

void SizeWeights::set(Op op, int weight) {
  if (weight < 1 || weight > 100)
    throw InvalidArgument(fmt::format("a size weight must be an integer in [1, 100], got {}", weight));
  weight_[static_cast<std::size_t>(op)] = weight;
}

SizeWeights SizeWeights::parse(std::string_view text) {
  SizeWeights w;
  if (text == "default" || text.empty()) return w;
  if (text == "turingbot") {
    w.set(Op::div, 2);
    return w;
  }
  for (std::string_view item : split(text, ',')) {
    const auto eq = item.find('=');
    const auto op = eq == std::string_view::npos ? std::nullopt : operator_named(item.substr(0, eq));
    if (!op)
      throw InvalidArgument(fmt::format(
          "bad size weight '{}' (expected default, turingbot or a list like \"/=2,sqrt=3\")", item));
    const double weight = io::parse_number(item.substr(eq + 1), "size weight");
    if (weight != std::floor(weight))
      throw InvalidArgument(fmt::format("size weight of '{}' must be an integer", item.substr(0, eq)));
    w.set(*op, static_cast<int>(weight));
  }
  return w;
}

std::vector<Op> parse_operators(std::string_view text) {
  std::vector<Op> ops;
  for (std::string_view name : split(text, ',')) {
    const auto op = operator_named(name);
    if (!op || expr::arity(*op) == 0)
      throw InvalidArgument(
          fmt::format("unknown operator '{}' (expected some of: {})", name, operator_names()));
    if (std::find(ops.begin(), ops.end(), *op) == ops.end()) ops.push_back(*op);
  }
  return ops;
}

std::string operator_names() {
  std::string names;
  for (std::size_t i = 0; i < expr::kOpCount; ++i) {
    const auto op = static_cast<Op>(i);
    if (expr::arity(op) == 0) continue;
    if (!names.empty()) names += ' ';
    names += operator_symbol(op);
    if (op == Op::pow) names += " pow";
  }
  return names;
}

namespace {

std::size_t knee(const std::vector<Candidate>& front, const auto& ranking_error) {
  const auto log_error = [&](const Candidate& c) {
    return std::log10(std::max(ranking_error(c), 1e-300));
  };
  const double x0 = front.front().size, x1 = front.back().size;
  const double y0 = log_error(front.front()), y1 = log_error(front.back());
  if (x1 <= x0 || y0 <= y1) return front.size() - 1;
  std::size_t best = 0;
  double deepest = 0;
  for (std::size_t i = 0; i < front.size(); ++i) {
    const double x = (front[i].size - x0) / (x1 - x0), y = (log_error(front[i]) - y1) / (y0 - y1);
    if (1 - x - y > deepest) {
      deepest = 1 - x - y;
      best = i;
    }
  }
  return best;
}

// v to `digits` significant digits, read back by from_chars: a subnormal stays one (stod throws
// on it); a rounding past the largest double (1.8e308 to 1 digit) keeps v.
double rounded_to(double v, int digits) {
  const std::string text = fmt::format("{:.{}g}", v, digits);
  double out = v;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), out);
  return error == std::errc{} && end == text.data() + text.size() ? out : v;
}

}  // namespace

/// The rounding step of v's shortest decimal (0.001 for 12.345, 1 for 1200): the last digit that
/// reads v back exactly.
double decimal_step(double v) {
  for (int digits = 1; digits <= 17; ++digits) {
    const std::string text = fmt::format("{:.{}e}", v, digits - 1);
    if (std::strtod(text.c_str(), nullptr) == v) return std::pow(10.0, std::floor(std::log10(std::abs(v))) - digits + 1);
  }
  return 0;
}

double noise_floor(std::span<const double> target, Metric metric, double best_loss) {
  if (metric == Metric::mean_relative || metric == Metric::max_rel || metric == Metric::r2) return 1e-10;
  double mean_square = 0;
  for (double y : target) mean_square += y * y / static_cast<double>(target.size());
  const double floor = 1e-10 * std::sqrt(mean_square);
  if (metric != Metric::rms) return floor;
  // Up to kDecimalSamples rows, evenly spread, tell the decimals (each reading costs 17 formats).
  constexpr std::size_t kDecimalSamples = 1000;
  std::vector<double> steps;
  const std::size_t stride = std::max<std::size_t>(1, target.size() / kDecimalSamples);
  for (std::size_t r = 0; r < target.size(); r += stride)
    if (target[r] != 0) steps.push_back(decimal_step(target[r]));
  if (steps.empty()) return floor;
  // RMS only: the rounding of the decimals (uniform, step/√12), where the best formula does not fit
  // below it. The median step: 12.300 reads as 12.3, one value in ten, and its step is no guide.
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  const double decimals = steps[steps.size() / 2] / std::sqrt(12.0);
  return best_loss >= 0.5 * decimals ? std::max(floor, 1.25 * decimals) : floor;
}

std::size_t choose(const std::vector<Candidate>& front, Metric metric, Choice choice, double factor,
                   double noise_floor) {
  if (front.empty()) throw InvalidArgument("cannot choose from an empty front");
  const auto ranking_error = [metric](const Candidate& c) {
    const double loss = to_loss(metric, c.test_error.value_or(c.train_error));
    return c.printed_error ? std::max(loss, to_loss(metric, *c.printed_error)) : loss;
  };
  std::size_t best = 0;
  for (std::size_t i = 1; i < front.size(); ++i)
    if (ranking_error(front[i]) < ranking_error(front[best])) best = i;
  if (choice == Choice::best) return best;
  if (choice == Choice::knee) return knee(front, ranking_error);
  const double tolerance = std::max(factor * ranking_error(front[best]), noise_floor);
  for (std::size_t i = 0; i < front.size(); ++i)
    if (ranking_error(front[i]) <= tolerance) return i;
  return best;
}

expr::Expression rounded(const expr::Expression& e, int digits) {
  std::vector<expr::Node> nodes(e.nodes().begin(), e.nodes().end());
  for (auto& n : nodes)
    if (n.op == Op::constant && !expr::is_exact(n)) n.value = rounded_to(n.value, digits);
  return expr::Expression(std::move(nodes), e.variables());
}

expr::Expression float_constants(const expr::Expression& e) {
  std::vector<expr::Node> nodes(e.nodes().begin(), e.nodes().end());
  for (auto& n : nodes) {
    if (n.op != Op::constant) continue;
    float value = static_cast<float>(n.value);
    if (expr::is_exact(n)) {
      value = static_cast<float>(n.numerator);
      if (n.symbol != expr::Symbol::one) value *= static_cast<float>(expr::symbol_value(n.symbol));
      value /= static_cast<float>(n.denominator);
    }
    n = expr::Node{Op::constant, 0, value};
  }
  return expr::Expression(std::move(nodes), e.variables());
}

}  // namespace specula::fit
