// specula::expr::Expression: op metadata and the well-formedness checks every expression passes.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <numbers>

#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

struct FunctionName {
  std::string_view name;
  Op op;
};

constexpr std::array kFunctions{
    FunctionName{"log", Op::log},   FunctionName{"log2", Op::log2}, FunctionName{"exp", Op::exp},
    FunctionName{"sqrt", Op::sqrt}, FunctionName{"abs", Op::abs},   FunctionName{"sin", Op::sin},
    FunctionName{"cos", Op::cos},   FunctionName{"acos", Op::acos}, FunctionName{"pow", Op::pow},
    FunctionName{"min", Op::min},   FunctionName{"max", Op::max},   FunctionName{"expm1", Op::expm1},
    FunctionName{"log1p", Op::log1p}, FunctionName{"asin", Op::asin},
};

bool is_identifier(std::string_view name) {
  const auto letter = [](char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
  };
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  return !name.empty() && letter(name.front()) &&
         std::all_of(name.begin(), name.end(), [&](char c) { return letter(c) || digit(c); });
}

void check_variable_names(const std::vector<std::string>& variables) {
  for (std::size_t i = 0; i < variables.size(); ++i) {
    const std::string& name = variables[i];
    if (!is_identifier(name) || is_reserved_call(name))
      throw InvalidArgument(fmt::format("invalid variable name '{}'", name));
    if (std::find(variables.begin(), variables.begin() + static_cast<std::ptrdiff_t>(i), name) !=
        variables.begin() + static_cast<std::ptrdiff_t>(i))
      throw InvalidArgument(fmt::format("variable '{}' is listed twice", name));
  }
}

void check_leaf(const Node& node, std::size_t variable_count) {
  if (node.op == Op::constant && !std::isfinite(node.value))
    throw InvalidArgument(fmt::format("expression constant {} is not finite", node.value));
  if (node.op == Op::variable && node.var >= variable_count)
    throw InvalidArgument(fmt::format("expression variable index {} is out of range", node.var));
}

// The stack depth postfix `nodes` needs; throws unless they leave exactly one value.
std::size_t checked_stack_depth(const std::vector<Node>& nodes, std::size_t variable_count) {
  std::size_t depth = 0;
  std::size_t deepest = 0;
  for (const Node& node : nodes) {
    const auto operands = static_cast<std::size_t>(arity(node.op));
    if (depth < operands) throw InvalidArgument("malformed expression: an operator lacks operands");
    check_leaf(node, variable_count);
    depth = depth - operands + 1;
    deepest = std::max(deepest, depth);
  }
  if (depth != 1) throw InvalidArgument("malformed expression: it must leave exactly one value");
  return deepest;
}

}  // namespace

double symbol_value(Symbol symbol) {
  switch (symbol) {
    case Symbol::one: return 1;
    case Symbol::pi: return std::numbers::pi;
    case Symbol::e: return std::numbers::e;
    case Symbol::ln2: return std::log(2.0);
    case Symbol::sqrt2: return std::sqrt(2.0);
    case Symbol::sqrt3: return std::sqrt(3.0);
  }
  unreachable();
}

Node exact_constant(int numerator, int denominator, Symbol symbol) {
  const double scaled = symbol == Symbol::one ? double(numerator) : double(numerator) * symbol_value(symbol);
  return Node{Op::constant, 0, denominator == 1 ? scaled : scaled / double(denominator),
              static_cast<std::int16_t>(numerator), static_cast<std::uint8_t>(denominator), symbol};
}

std::vector<bool> exact_only_subtrees(std::span<const Node> nodes) {
  std::vector<bool> out(nodes.size());
  std::vector<std::size_t> roots;  // the subtrees on the stack
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto operands = std::min(static_cast<std::size_t>(arity(nodes[i].op)), roots.size());
    bool exact = operands > 0 || is_exact(nodes[i]);
    for (std::size_t k = roots.size() - operands; k < roots.size(); ++k) exact = exact && out[roots[k]];
    roots.resize(roots.size() - operands);
    roots.push_back(i);
    out[i] = exact;
  }
  return out;
}

int arity(Op op) {
  switch (op) {
    case Op::constant:
    case Op::variable: return 0;
    case Op::add:
    case Op::sub:
    case Op::mul:
    case Op::div:
    case Op::pow:
    case Op::min:
    case Op::max: return 2;
    case Op::neg:
    case Op::log:
    case Op::log2:
    case Op::exp:
    case Op::sqrt:
    case Op::abs:
    case Op::sin:
    case Op::cos:
    case Op::acos:
    case Op::expm1:
    case Op::log1p:
    case Op::asin: return 1;
  }
  throw InvalidArgument(fmt::format("unknown expression op {}", static_cast<int>(op)));
}

std::string_view function_name(Op op) {
  const auto* found = std::find_if(kFunctions.begin(), kFunctions.end(),
                                   [op](const FunctionName& f) { return f.op == op; });
  return found == kFunctions.end() ? std::string_view{} : found->name;
}

std::optional<Op> function_named(std::string_view name) {
  const auto* found = std::find_if(kFunctions.begin(), kFunctions.end(),
                                   [name](const FunctionName& f) { return f.name == name; });
  if (found == kFunctions.end()) return std::nullopt;
  return found->op;
}

Expression::Expression(std::vector<Node> nodes, std::vector<std::string> variables)
    : nodes_(std::move(nodes)), variables_(std::move(variables)) {
  check_variable_names(variables_);
  stack_depth_ = checked_stack_depth(nodes_, variables_.size());
}

}  // namespace specula::expr
