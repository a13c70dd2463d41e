// specula::expr printers: infix, C++, GLSL, LaTeX and Python text from postfix nodes. One driver
// turns the postfix array into fragments; each dialect says how a node combines its operands.
#include <cmath>
#include <fmt/format.h>

#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

// How tightly a fragment binds; an operand binding looser than its context gets parentheses.
enum Precedence { kSum = 1, kProduct = 2, kNegation = 3, kPower = 4, kAtom = 5 };

struct Fragment {
  std::string text;
  int precedence = kAtom;
};

using Operands = std::span<const Fragment>;
using Combine = Fragment (*)(const Node& node, Operands operands, const Expression& e);

std::string render(const Expression& e, Combine combine) {
  std::vector<Fragment> stack;
  for (const Node& node : e.nodes()) {
    const auto operands = static_cast<std::size_t>(arity(node.op));
    Fragment combined = combine(node, Operands(stack).last(operands), e);
    stack.resize(stack.size() - operands);
    stack.push_back(std::move(combined));
  }
  return stack.back().text;
}

std::string wrapped(const Fragment& f, bool parenthesize) {
  return parenthesize ? "(" + f.text + ")" : f.text;
}

// A signed number from the text of its magnitude: negative numbers bind like unary minus.
Fragment signed_number(double value, std::string magnitude) {
  if (std::signbit(value)) return {"-" + magnitude, kNegation};
  return {std::move(magnitude), kAtom};
}

// Shortest text that reads back as exactly `magnitude`, made a floating literal if `literal`.
std::string shortest(double magnitude, bool literal) {
  std::string text = fmt::format("{}", magnitude);
  if (literal && text.find_first_of(".e") == std::string::npos) text += ".0";
  return text;
}

// GLSL float literal: the nearest float, shortest, always with a decimal point.
std::string glsl_float(double magnitude) {
  const auto single = static_cast<float>(magnitude);
  std::string text =
      std::isfinite(single) ? fmt::format("{}", single) : fmt::format("{}", magnitude);
  const auto exponent = text.find('e');
  const std::string mantissa = text.substr(0, exponent);
  const std::string suffix = exponent == std::string::npos ? "" : text.substr(exponent);
  return mantissa.find('.') == std::string::npos ? mantissa + ".0" + suffix : text;
}

Fragment negation(const Fragment& operand) {
  std::string text(1, '-');  // not "-" + …: GCC 12 warns falsely (-Wrestrict) on that form
  text += wrapped(operand, operand.precedence <= kNegation);
  return {std::move(text), kNegation};
}

// a op b for the left-associative + - * / or the right-associative power operator.
Fragment infix(Operands operands, std::string_view symbol, int precedence) {
  const Fragment& left = operands[0];
  const Fragment& right = operands[1];
  const bool power = precedence == kPower;
  const bool wrap_left = power ? left.precedence <= kPower : left.precedence < precedence;
  const bool wrap_right = power ? right.precedence < kNegation : right.precedence <= precedence;
  return {fmt::format("{} {} {}", wrapped(left, wrap_left), symbol, wrapped(right, wrap_right)),
          precedence};
}

Fragment call(std::string_view name, Operands operands) {
  std::string text = std::string(name) + "(" + operands[0].text;
  if (operands.size() == 2) text += ", " + operands[1].text;
  return {text + ")", kAtom};
}

// The parts every dialect but LaTeX shares: leaves, negation and + - * /.
std::optional<Fragment> common(const Node& node, Operands operands, const Expression& e) {
  switch (node.op) {
    case Op::variable: return Fragment{e.variables()[node.var], kAtom};
    case Op::neg: return negation(operands[0]);
    case Op::add: return infix(operands, "+", kSum);
    case Op::sub: return infix(operands, "-", kSum);
    case Op::mul: return infix(operands, "*", kProduct);
    case Op::div: return infix(operands, "/", kProduct);
    case Op::constant:
    case Op::pow:
    case Op::min:
    case Op::max:
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
    case Op::asin: return std::nullopt;  // each dialect's own
  }
  unreachable();
}

// A negation of a negation reads "- -x": "-(-x)" nests two levels deeper per sign than the "--x"
// it may have been parsed from, so a text parse() accepted near kMaxNesting would not read back.
Fragment infix_negation(const Fragment& operand) {
  if (operand.precedence != kNegation) return negation(operand);
  std::string text("- ");
  text += operand.text;
  return {std::move(text), kNegation};
}

Fragment infix_node(const Node& node, Operands operands, const Expression& e) {
  if (node.op == Op::constant)
    return signed_number(node.value, shortest(std::abs(node.value), false));
  if (node.op == Op::pow) return infix(operands, "^", kPower);
  if (node.op == Op::neg) return infix_negation(operands[0]);
  if (auto done = common(node, operands, e)) return *done;
  return call(function_name(node.op), operands);
}

Fragment cpp_node(const Node& node, Operands operands, const Expression& e) {
  if (node.op == Op::constant)
    return signed_number(node.value, shortest(std::abs(node.value), true));
  if (auto done = common(node, operands, e)) return *done;
  return call("std::" + std::string(function_name(node.op)), operands);
}

Fragment glsl_node(const Node& node, Operands operands, const Expression& e) {
  if (node.op == Op::constant) return signed_number(node.value, glsl_float(std::abs(node.value)));
  if (auto done = common(node, operands, e)) return *done;
  // GLSL has neither: the plain forms (float precision hides their cancellation near 0 anyway).
  if (node.op == Op::expm1) return {"(exp(" + operands[0].text + ") - 1.0)", kAtom};
  if (node.op == Op::log1p) return {"log(1.0 + " + operands[0].text + ")", kAtom};
  return call(function_name(node.op), operands);
}

std::string python_name(Op op) {
  const std::string_view name = function_name(op);
  if (op == Op::abs || op == Op::min || op == Op::max) return std::string(name);
  return "math." + std::string(name);
}

Fragment python_node(const Node& node, Operands operands, const Expression& e) {
  if (node.op == Op::constant)
    return signed_number(node.value, shortest(std::abs(node.value), true));
  if (node.op == Op::pow) return infix(operands, "**", kPower);
  if (auto done = common(node, operands, e)) return *done;
  return call(python_name(node.op), operands);
}

// ---- LaTeX ----------------------------------------------------------------------------------

// 1e-05 becomes 1 \cdot 10^{-5}, binding like a product.
Fragment latex_number(double value) {
  const std::string text = shortest(std::abs(value), false);
  const auto exponent = text.find('e');
  if (exponent == std::string::npos) return signed_number(value, text);
  const int power = std::stoi(text.substr(exponent + 1));
  const std::string sign = std::signbit(value) ? "-" : "";
  return {fmt::format("{}{} \\cdot 10^{{{}}}", sign, text.substr(0, exponent), power), kProduct};
}

std::string latex_parenthesized(const Fragment& f) { return "\\left(" + f.text + "\\right)"; }

Fragment latex_power(Operands operands) {
  const Fragment& base = operands[0];
  const std::string shown = base.precedence == kAtom && base.text.find('\\') == std::string::npos
                                ? base.text
                                : latex_parenthesized(base);
  return {fmt::format("{}^{{{}}}", shown, operands[1].text), kPower};
}

Fragment latex_call(std::string_view name, Operands operands) {
  std::string inside = operands[0].text;
  if (operands.size() == 2) inside += ", " + operands[1].text;
  return {std::string(name) + "\\left(" + inside + "\\right)", kAtom};
}

std::string_view latex_function(Op op) {
  switch (op) {
    case Op::log: return "\\log";
    case Op::log2: return "\\log_2";
    case Op::exp: return "\\exp";
    case Op::sin: return "\\sin";
    case Op::cos: return "\\cos";
    case Op::acos: return "\\arccos";
    case Op::asin: return "\\arcsin";
    case Op::expm1: return "\\operatorname{expm1}";
    case Op::log1p: return "\\operatorname{log1p}";
    case Op::min: return "\\min";
    case Op::max: return "\\max";
    case Op::constant:
    case Op::variable:
    case Op::add:
    case Op::sub:
    case Op::mul:
    case Op::div:
    case Op::pow:
    case Op::neg:
    case Op::sqrt:
    case Op::abs: break;  // latex_node writes these itself
  }
  unreachable();
}

Fragment latex_node(const Node& node, Operands operands, const Expression& e) {
  switch (node.op) {
    case Op::constant: return latex_number(node.value);
    case Op::variable: return {e.variables()[node.var], kAtom};
    case Op::neg: return negation(operands[0]);
    case Op::add: return infix(operands, "+", kSum);
    case Op::sub: return infix(operands, "-", kSum);
    case Op::mul: return infix(operands, "\\cdot", kProduct);
    case Op::div:
      return {fmt::format("\\frac{{{}}}{{{}}}", operands[0].text, operands[1].text), kAtom};
    case Op::pow: return latex_power(operands);
    case Op::sqrt: return {"\\sqrt{" + operands[0].text + "}", kAtom};
    case Op::abs: return {"\\left|" + operands[0].text + "\\right|", kAtom};
    case Op::min:
    case Op::max:
    case Op::log:
    case Op::log2:
    case Op::exp:
    case Op::sin:
    case Op::cos:
    case Op::acos:
    case Op::expm1:
    case Op::log1p:
    case Op::asin: return latex_call(latex_function(node.op), operands);
  }
  unreachable();
}

}  // namespace

std::string to_infix(const Expression& e) { return render(e, infix_node); }
std::string to_cpp(const Expression& e) { return render(e, cpp_node); }
std::string to_glsl(const Expression& e) { return render(e, glsl_node); }
std::string to_latex(const Expression& e) { return render(e, latex_node); }
std::string to_python(const Expression& e) { return render(e, python_node); }

}  // namespace specula::expr
