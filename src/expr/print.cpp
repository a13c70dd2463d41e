// specula::expr printers: infix, C++, GLSL, LaTeX and Python text from postfix nodes. One driver
// turns the postfix array into fragments; each dialect says how a node combines its operands.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

// How tightly a fragment binds; an operand binding looser than its context gets parentheses.
enum Precedence { kSum = 1, kProduct = 2, kNegation = 3, kPower = 4, kAtom = 5 };

struct Fragment {
  Fragment() = default;
  Fragment(std::string t, int p = kAtom) : text(std::move(t)), precedence(p) {}
  std::string text;
  int precedence = kAtom;
  /// Built of exact constants only (set by render()).
  bool exact_only = false;
  /// An exact constant written as a decimal (0.5), as the fraction it is ("1 / 2"): how the infix
  /// writes it inside an elementary constant, where a CAS must read it exactly (exp(-1 / 2)).
  std::string fraction{};
};

using Operands = std::span<const Fragment>;
using Combine = Fragment (*)(const Node& node, Operands operands, const Expression& e);

std::string render(const Expression& e, Combine combine) {
  std::vector<Fragment> stack;
  const std::vector<bool> exact_only = exact_only_subtrees(e.nodes());
  for (std::size_t i = 0; i < e.nodes().size(); ++i) {
    const Node& node = e.nodes()[i];
    const auto operands = static_cast<std::size_t>(arity(node.op));
    Fragment combined = combine(node, Operands(stack).last(operands), e);
    combined.exact_only = exact_only[i];
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

/// How a dialect writes the parts of an exact constant (Node::numerator · symbol / denominator).
struct ExactTexts {
  std::string (*number)(double magnitude);
  std::array<std::string_view, kSymbolCount> symbols;  ///< by Symbol; Symbol::one unused
  std::string_view times;                               ///< between the numerator and the symbol
};

/// p · s / q as the dialect writes it, binding like a product (like a negation or an atom where
/// there is no operator: "-pi", "pi", "3").
Fragment exact(const Node& node, const ExactTexts& texts) {
  const int p = std::abs(int(node.numerator)), q = node.denominator;
  // Halves, quarters, fifths, eighths and tenths read best as the decimals they are: 0.5, 0.25.
  if (node.symbol == Symbol::one && (q == 2 || q == 4 || q == 5 || q == 8 || q == 10)) {
    Fragment decimal = signed_number(node.value, texts.number(std::abs(node.value)));
    decimal.fraction = fmt::format("{}{} / {}", node.numerator < 0 ? "-" : "", texts.number(p), texts.number(q));
    return decimal;
  }
  const std::string_view symbol = texts.symbols[static_cast<std::size_t>(node.symbol)];
  std::string text;
  int precedence = kAtom;
  if (node.symbol == Symbol::one) {
    text = texts.number(p);
  } else if (p == 1) {
    text = symbol;
  } else {
    text = texts.number(p) + std::string(texts.times) + std::string(symbol);
    precedence = kProduct;
  }
  if (q > 1) {
    text += " / " + texts.number(q);
    precedence = kProduct;
  }
  if (node.numerator < 0) {
    text.insert(0, 1, '-');
    precedence = std::min(precedence, int(kNegation));
  }
  return {std::move(text), precedence};
}

std::string plain_number(double magnitude) { return shortest(magnitude, false); }
std::string literal_number(double magnitude) { return shortest(magnitude, true); }
std::string glsl_number(double magnitude) { return glsl_float(magnitude); }

const ExactTexts kInfixExact{plain_number, {"", "pi", "exp(1)", "log(2)", "sqrt(2)", "sqrt(3)"}, " * "};
const ExactTexts kCppExact{literal_number,
                           {"", "std::numbers::pi", "std::numbers::e", "std::numbers::ln2", "std::numbers::sqrt2",
                            "std::numbers::sqrt3"},
                           " * "};
const ExactTexts kPythonExact{literal_number,
                              {"", "math.pi", "math.e", "math.log(2)", "math.sqrt(2)", "math.sqrt(3)"}, " * "};

/// GLSL has no named constants: the symbols' float values (still written p * s / q).
Fragment glsl_exact(const Node& node) {
  static const std::array<std::string, kSymbolCount> values = [] {
    std::array<std::string, kSymbolCount> out;
    for (std::size_t i = 1; i < kSymbolCount; ++i) out[i] = glsl_float(symbol_value(static_cast<Symbol>(i)));
    return out;
  }();
  const ExactTexts texts{glsl_number, {"", values[1], values[2], values[3], values[4], values[5]}, " * "};
  return exact(node, texts);
}

Fragment negation(const Fragment& operand) {
  std::string text(1, '-');  // not "-" + …: GCC 12 warns falsely (-Wrestrict) on that form
  text += wrapped(operand, operand.precedence <= kNegation);
  return {std::move(text), kNegation};
}

/// The text of −X without its sign when it is written "-X" (a negative number or a product or
/// power that leads with one); empty otherwise. a + −X and a − X compute the same in IEEE
/// arithmetic, sign for sign, so a sum writes "a - X" (and a difference "a + X").
std::string without_leading_minus(const Fragment& f) {
  // Not "-(…)": the magnitude would keep parentheses that reading it back drops.
  const bool signed_term = f.precedence >= kProduct && f.text.size() > 1 && f.text[0] == '-' && f.text[1] != ' ' &&
                           f.text[1] != '-' && f.text[1] != '(';
  return signed_term ? f.text.substr(1) : std::string();
}

// a op b for the left-associative + - * / or the right-associative power operator.
Fragment infix(Operands operands, std::string_view symbol, int precedence) {
  const Fragment& left = operands[0];
  const Fragment& right = operands[1];
  if (precedence == kSum) {
    if (std::string magnitude = without_leading_minus(right); !magnitude.empty()) {
      const std::string_view flipped = symbol == "+" ? "-" : "+";
      return {fmt::format("{} {} {}", wrapped(left, left.precedence < kSum), flipped, magnitude), kSum};
    }
  }
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

Fragment infix_node(const Node& node, Operands given, const Expression& e) {
  if (is_exact(node)) return exact(node, kInfixExact);
  // Inside an elementary constant a function's or a power's decimals are written as fractions:
  // exp(-1 / 2), not exp(-0.5), which SymPy would evaluate to a float.
  std::vector<Fragment> as_fractions(given.begin(), given.end());
  if (node.op != Op::mul && node.op != Op::div && node.op != Op::add && node.op != Op::sub &&
      std::ranges::all_of(given, &Fragment::exact_only))
    for (Fragment& f : as_fractions)
      if (!f.fraction.empty()) f = Fragment(f.fraction, kProduct);
  const Operands operands(as_fractions);
  if (node.op == Op::constant)
    return signed_number(node.value, shortest(std::abs(node.value), false));
  if (node.op == Op::pow) return infix(operands, "^", kPower);
  if (node.op == Op::neg) return infix_negation(operands[0]);
  if (auto done = common(node, operands, e)) return *done;
  return call(function_name(node.op), operands);
}

Fragment cpp_node(const Node& node, Operands operands, const Expression& e) {
  if (is_exact(node)) return exact(node, kCppExact);
  if (node.op == Op::constant)
    return signed_number(node.value, shortest(std::abs(node.value), true));
  if (auto done = common(node, operands, e)) return *done;
  return call("std::" + std::string(function_name(node.op)), operands);
}

// GLSL's pow(x, y) is undefined for x < 0 (NaN on GPUs), where an integer power is not: an even
// power is pow(abs(x), k), an odd one x·pow(abs(x), k − 1) (compilers turn small ones into
// products; abs is free on GPUs). nullopt where the exponent is not a whole number ("2.0").
std::optional<Fragment> glsl_integer_power(Operands operands) {
  const std::string& k = operands[1].text;
  if (k.size() < 3 || !k.ends_with(".0") || k.find_first_not_of("-0123456789", 0) != k.size() - 2) return std::nullopt;
  const long long power = std::stoll(k.substr(0, k.size() - 2));
  const std::string& x = operands[0].text;
  if (power % 2 == 0) return Fragment{fmt::format("pow(abs({}), {})", x, k), kAtom};
  return Fragment{fmt::format("({}) * pow(abs({}), {}.0)", x, x, power - 1), kProduct};
}

Fragment glsl_node(const Node& node, Operands operands, const Expression& e) {
  if (is_exact(node)) return glsl_exact(node);
  if (node.op == Op::constant) return signed_number(node.value, glsl_float(std::abs(node.value)));
  if (auto done = common(node, operands, e)) return *done;
  if (node.op == Op::pow)
    if (auto power = glsl_integer_power(operands)) return *power;
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
  if (is_exact(node)) return exact(node, kPythonExact);
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

/// \frac{p s}{q}, or p s where q = 1.
Fragment latex_exact(const Node& node) {
  static constexpr std::array<std::string_view, kSymbolCount> kSymbols{"", "\\pi", "e", "\\ln 2", "\\sqrt{2}", "\\sqrt{3}"};
  const int p = std::abs(int(node.numerator)), q = node.denominator;
  const std::string_view symbol = kSymbols[static_cast<std::size_t>(node.symbol)];
  std::string top = node.symbol == Symbol::one ? std::to_string(p) : (p == 1 ? "" : std::to_string(p)) + std::string(symbol);
  std::string text = q > 1 ? fmt::format("\\frac{{{}}}{{{}}}", top, q) : top;
  if (node.numerator < 0) return {"-" + text, kNegation};
  return {std::move(text), kAtom};
}

Fragment latex_node(const Node& node, Operands operands, const Expression& e) {
  if (is_exact(node)) return latex_exact(node);
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
