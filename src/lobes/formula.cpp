// lobes::Formula: evaluation through expr::Program, and the numerical search for the support
// end, the half-maximum and the kinks (lobes/formula.h). The search checks the work limit
// (specula/interrupt) every kPointsPerCheck grid points and before each bisection: one point of
// a long formula with many min/max costs up to a few hundred thousand operations.
#include "specula/lobes/formula.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>

#include "specula/interrupt/interrupt.h"

namespace specula::lobes {
namespace {

constexpr std::size_t kGridSize = 2000;
constexpr double kGridLow = 1e-20;
constexpr double kGridHigh = 64;
constexpr std::size_t kMaxKinks = 64;
constexpr std::size_t kPointsPerCheck = 64;

std::vector<double> log_cos_grid() {
  std::vector<double> u(kGridSize);
  const double ratio = std::log(kGridHigh / kGridLow) / double(kGridSize - 1);
  for (std::size_t i = 0; i < kGridSize; ++i) u[i] = kGridLow * std::exp(ratio * double(i));
  u.back() = kGridHigh;
  return u;
}

const std::vector<double>& grid() {
  static const std::vector<double> u = log_cos_grid();
  return u;
}

/// The boundary between a (where inside(a)) and b (where !inside(b)), to the last bit.
template <class Inside>
double bisect(double a, double b, const Inside& inside) {
  check_interrupt();
  for (int i = 0; i < 200; ++i) {
    const double mid = a + (b - a) / 2;
    if (mid == a || mid == b) break;
    (inside(mid) ? a : b) = mid;
  }
  return b;
}

/// For every node of `e`, the index of the first node of its subtree (postfix order).
std::vector<std::size_t> subtree_starts(const expr::Expression& e) {
  const auto nodes = e.nodes();
  std::vector<std::size_t> start(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int operands = expr::arity(nodes[i].op);
    if (operands == 0) start[i] = i;
    else if (operands == 1) start[i] = start[i - 1];
    else start[i] = start[start[i - 1] - 1];
  }
  return start;
}

/// The expressions whose sign changes are the kinks of `e`: a − b for min(a, b) and max(a, b),
/// a for abs(a).
std::vector<expr::Expression> switch_arguments(const expr::Expression& e) {
  using expr::Node, expr::Op;
  const auto nodes = e.nodes();
  const auto start = subtree_starts(e);
  std::vector<expr::Expression> out;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Op op = nodes[i].op;
    if (op != Op::min && op != Op::max && op != Op::abs) continue;
    std::vector<Node> diff(nodes.begin() + static_cast<std::ptrdiff_t>(start[i]),
                           nodes.begin() + static_cast<std::ptrdiff_t>(i));
    if (op != Op::abs) diff.push_back(Node{Op::sub});
    out.emplace_back(std::move(diff), e.variables());
  }
  return out;
}

}  // namespace

Formula::Formula(std::shared_ptr<const FormulaDefinition> definition, std::vector<double> params)
    : definition_(std::move(definition)), params_(std::move(params)) {
  const expr::Program& program = definition_->any();
  if (params_.size() != program.param_count())
    throw InvalidArgument(fmt::format("the lobe formula has {} parameters but {} values were given",
                                      program.param_count(), params_.size()));
  const auto& u = grid();
  std::vector<double> f(u.size());
  for (std::size_t i = 0; i < u.size(); ++i) {
    if (i % kPointsPerCheck == 0) check_interrupt();
    f[i] = at_log_cos(u[i]);
  }

  // Support: the end of the last nonzero stretch (F ≠ 0 at the grid's end: none).
  std::size_t last = u.size();
  while (last > 0 && f[last - 1] == 0) --last;
  if (last == 0) support_ = 0;
  else if (last < u.size())
    support_ = bisect(u[last - 1], u[last], [&](double x) { return at_log_cos(x) != 0; });

  // Half-maximum: where F first falls below half its value at c = 1.
  const double half = at_log_cos(0) / 2;
  const auto below = std::find_if(f.begin(), f.end(), [&](double v) { return v < half; });
  if (below == f.begin()) half_max_ = u.front();
  else if (below != f.end()) {
    const auto j = static_cast<std::size_t>(below - f.begin());
    half_max_ = bisect(u[j - 1], u[j], [&](double x) { return !(at_log_cos(x) < half); });
  } else half_max_ = std::isfinite(support_) && support_ > 0 ? support_ : 1.0;

  // Kinks: sign changes of every min/max/abs argument, in any step, before the support end. One
  // sweep evaluates the program (its lets) once per grid point and every argument there; each
  // sign change found is then refined by bisection.
  std::array<double, expr::kMaxSlots> slots{};
  std::copy(params_.begin(), params_.end(), slots.begin() + 2);
  auto set_point = [&](double x) {
    slots[0] = std::exp(-x);
    slots[1] = x;
    (void)program.evaluate(std::span<double>(slots.data(), program.slot_names().size()));
  };
  std::vector<expr::Expression> arguments;
  for (const auto& step : program.lets())
    for (auto& a : switch_arguments(step)) arguments.push_back(std::move(a));
  for (auto& a : switch_arguments(program.result())) arguments.push_back(std::move(a));
  struct SignChange {
    std::size_t argument, point;  // between u[point − 1] and u[point]
    bool positive_first;
  };
  std::vector<SignChange> changes;
  std::vector<double> previous(arguments.size());
  set_point(u[0]);
  for (std::size_t a = 0; a < arguments.size(); ++a) previous[a] = expr::evaluate_unchecked(arguments[a], slots);
  for (std::size_t i = 1; i < u.size() && u[i - 1] < support_ && changes.size() < kMaxKinks; ++i) {
    if (i % kPointsPerCheck == 0) check_interrupt();
    set_point(u[i]);
    for (std::size_t a = 0; a < arguments.size(); ++a) {
      const double value = expr::evaluate_unchecked(arguments[a], slots);
      if ((previous[a] > 0) != (value > 0) && !std::isnan(previous[a]) && !std::isnan(value))
        changes.push_back({a, i, previous[a] > 0});
      previous[a] = value;
    }
  }
  for (const SignChange& change : changes) {
    const double kink = bisect(u[change.point - 1], u[change.point], [&](double x) {
      set_point(x);
      return (expr::evaluate_unchecked(arguments[change.argument], slots) > 0) == change.positive_first;
    });
    if (kink < support_) kinks_.push_back(kink);
  }
  std::sort(kinks_.begin(), kinks_.end());
  kinks_.erase(std::unique(kinks_.begin(), kinks_.end()), kinks_.end());
}

double Formula::run(const expr::Program& program, double c, double u, bool c_of_u) const noexcept {
  std::array<double, expr::kMaxSlots> slots;
  if (c_of_u && program.reads(0)) c = std::exp(-u);
  if (!c_of_u && program.reads(1)) u = -std::log(c);
  slots[0] = c;
  slots[1] = u;
  std::copy(params_.begin(), params_.end(), slots.begin() + 2);
  return program.evaluate(std::span<double>(slots.data(), program.slot_names().size()));
}

double Formula::operator()(double c) const noexcept {
  if (!(c > 0)) return std::isnan(c) ? c : 0.0;
  const auto& program = definition_->in_cos ? *definition_->in_cos : *definition_->in_log_cos;
  return run(program, std::min(c, 1.0), 0, false);
}

double Formula::at_log_cos(double u) const noexcept {
  if (std::isnan(u)) return u;
  if (!(u < kInfinity<double>)) return 0;
  const auto& program = definition_->in_log_cos ? *definition_->in_log_cos : *definition_->in_cos;
  return run(program, 0, std::max(u, 0.0), true);
}

void Formula::eval_batch(std::span<const double> c, std::span<double> out) const {
  const std::size_t count = std::min(c.size(), out.size());
  const auto& program = definition_->in_cos ? *definition_->in_cos : *definition_->in_log_cos;
  std::vector<double> cs(count), us(count, 0.0);
  for (std::size_t i = 0; i < count; ++i) {
    cs[i] = c[i] > 0 ? std::min(c[i], 1.0) : 1.0;  // c ≤ 0 and NaN: set below
    if (program.reads(1)) us[i] = -std::log(cs[i]);
  }
  const std::span<const double> inputs[] = {cs, us};
  program.evaluate_batch(inputs, params_, out.first(count));
  for (std::size_t i = 0; i < count; ++i)
    if (!(c[i] > 0)) out[i] = std::isnan(c[i]) ? c[i] : 0.0;
}

}  // namespace specula::lobes
