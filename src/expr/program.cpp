// specula::expr::Program: named steps over one array of slots (expr/program.h).
#include "specula/expr/program.h"

#include <algorithm>
#include <array>
#include <fmt/format.h>
#include <numbers>

namespace specula::expr {
namespace {

struct NamedConstant {
  std::string_view name;
  double value;
};
constexpr std::array kConstants{NamedConstant{"pi", std::numbers::pi}, NamedConstant{"e", std::numbers::e}};

const NamedConstant* constant_named(std::string_view name) {
  for (const auto& c : kConstants)
    if (c.name == name) return &c;
  return nullptr;
}

// `e` with every variable at index ≥ first_constant replaced by its constant's value.
Expression bind_constants(const Expression& e, std::size_t first_constant) {
  std::vector<Node> nodes(e.nodes().begin(), e.nodes().end());
  for (Node& node : nodes) {
    if (node.op != Op::variable || node.var < first_constant) continue;
    node = Node{Op::constant, 0, kConstants[node.var - first_constant].value};
  }
  std::vector<std::string> variables(e.variables().begin(),
                                     e.variables().begin() + static_cast<std::ptrdiff_t>(first_constant));
  return Expression(std::move(nodes), std::move(variables));
}

}  // namespace

void require_slot_name(std::string_view name, std::string_view what) {
  if (constant_named(name))
    throw InvalidArgument(fmt::format("{} name '{}' is reserved for the constant {}", what, name, name));
  if (is_reserved_call(name))
    throw InvalidArgument(fmt::format("{} name '{}' is a function name", what, name));
  const bool identifier =
      !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
      std::all_of(name.begin(), name.end(),
                  [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
  if (!identifier)
    throw InvalidArgument(fmt::format("{} name '{}' is not an identifier (letters, digits, _)", what, name));
  // Shaders name a slot p_NAME or l_NAME, and GLSL reserves every identifier containing "__".
  if (name.front() == '_' || name.find("__") != std::string_view::npos)
    throw InvalidArgument(
        fmt::format("{} name '{}' may not start with _ or contain __ (reserved in GLSL)", what, name));
}

Program::Program(std::vector<std::string> inputs, std::vector<std::string> params)
    : inputs_(inputs.size()), params_(params.size()) {
  for (auto& name : inputs) slots_.push_back(std::move(name));
  for (auto& name : params) {
    require_slot_name(name, "parameter");
    if (std::find(slots_.begin(), slots_.end(), name) != slots_.end())
      throw InvalidArgument(fmt::format("parameter name '{}' is used twice (or is an input)", name));
    slots_.push_back(std::move(name));
  }
  if (slots_.size() > kMaxSlots)
    throw InvalidArgument(fmt::format("a formula may have at most {} inputs and parameters", kMaxSlots));
}

Expression Program::parse_step(std::string_view text) const {
  if (text.size() > kMaxFormulaLength)
    throw InvalidArgument(fmt::format("formula of {} characters is too long (at most {})", text.size(),
                                      kMaxFormulaLength));
  std::vector<std::string> names = slots_;
  for (const auto& c : kConstants) names.emplace_back(c.name);
  const Expression parsed = parse(text, std::move(names));
  if (parsed.stack_depth() > kMaxFormulaDepth)
    throw InvalidArgument(fmt::format("formula nests too deep (evaluation depth {}, at most {})",
                                      parsed.stack_depth(), kMaxFormulaDepth));
  return bind_constants(parsed, slots_.size());
}

void Program::let(std::string name, std::string_view text) {
  require_slot_name(name, "let");
  if (std::find(slots_.begin(), slots_.end(), name) != slots_.end())
    throw InvalidArgument(fmt::format("let '{}' is already defined (as an input, parameter or let)", name));
  if (slots_.size() >= kMaxSlots)
    throw InvalidArgument(fmt::format("a formula may have at most {} inputs, parameters and lets", kMaxSlots));
  lets_.push_back(parse_step(text));
  note_reads(lets_.back());
  slots_.push_back(std::move(name));
}

void Program::set_result(std::string_view text) {
  if (has_result_) throw InvalidArgument("a formula has one result");
  result_ = parse_step(text);
  note_reads(result_);
  has_result_ = true;
}

bool Program::reads(std::size_t slot) const noexcept { return slot < reads_.size() && reads_[slot]; }

void Program::note_reads(const Expression& e) {
  reads_.resize(kMaxSlots);
  for (const Node& n : e.nodes())
    if (n.op == Op::variable) reads_[n.var] = true;
}

double Program::evaluate(std::span<double> slots) const noexcept {
  const std::size_t first_let = inputs_ + params_;
  for (std::size_t i = 0; i < lets_.size(); ++i) slots[first_let + i] = evaluate_unchecked(lets_[i], slots);
  return evaluate_unchecked(result_, slots);
}

void Program::evaluate_batch(std::span<const std::span<const double>> inputs, std::span<const double> params,
                             std::span<double> out) const {
  constexpr std::size_t kRows = 256;
  const std::size_t fixed = inputs_ + params_;
  // Columns of one chunk: the inputs' rows, each parameter repeated, each let's values.
  std::vector<double> storage((params_ + lets_.size()) * kRows);
  for (std::size_t p = 0; p < params_; ++p) std::fill_n(storage.begin() + static_cast<std::ptrdiff_t>(p * kRows), kRows, params[p]);
  std::vector<std::span<const double>> columns(slots_.size());
  for (std::size_t first = 0; first < out.size(); first += kRows) {
    const std::size_t n = std::min(kRows, out.size() - first);
    for (std::size_t i = 0; i < inputs_; ++i) columns[i] = inputs[i].subspan(first, n);
    for (std::size_t j = inputs_; j < slots_.size(); ++j) columns[j] = {storage.data() + (j - inputs_) * kRows, n};
    for (std::size_t k = 0; k < lets_.size(); ++k) {
      double* let_out = storage.data() + (fixed - inputs_ + k) * kRows;
      expr::evaluate_batch(lets_[k], std::span(columns).first(fixed + k), {let_out, n});
    }
    expr::evaluate_batch(result_, columns, out.subspan(first, n));
  }
}

std::size_t Program::node_count() const noexcept {
  std::size_t count = result_.size();
  for (const auto& step : lets_) count += step.size();
  return count;
}

}  // namespace specula::expr
