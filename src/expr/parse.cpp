// specula::expr::parse: a recursive-descent parser from infix text to postfix nodes.
//   sum     := product (('+' | '-') product)*
//   product := unary (('*' | '/') unary)*
//   unary   := '-' unary | power
//   power   := primary ('^' unary)?
//   primary := number | variable | function '(' sum (',' sum)* ')' | '(' sum ')'
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "specula/expr/expr.h"

namespace specula::expr {
namespace {

enum class TokenKind { number, identifier, symbol, end };

struct Token {
  TokenKind kind = TokenKind::end;
  std::string_view text;
  std::size_t column = 1;
  double value = 0;
};

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }
bool starts_identifier(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool continues_identifier(char c) { return starts_identifier(c) || is_digit(c); }

std::string describe(const Token& token) {
  switch (token.kind) {
    case TokenKind::end: return "end of input";
    case TokenKind::number: return fmt::format("number '{}'", token.text);
    case TokenKind::identifier:
    case TokenKind::symbol: return fmt::format("'{}'", token.text);
  }
  unreachable();
}

[[noreturn]] void fail(std::size_t column, std::string_view message) {
  throw ParseError(column, message);
}

// Converts the text of a number token; underflow gives the nearest subnormal or zero.
double number_value(std::string_view text, std::size_t column) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error == std::errc::result_out_of_range)
    value = std::strtod(std::string(text).c_str(), nullptr);
  else if (error != std::errc{} || end != text.data() + text.size())
    fail(column, fmt::format("malformed number '{}'", text));
  if (!std::isfinite(value)) fail(column, fmt::format("number '{}' is out of range", text));
  return value;
}

class Parser {
 public:
  Parser(std::string_view text, std::vector<std::string> variables)
      : text_(text), variables_(std::move(variables)), fixed_variables_(!variables_.empty()) {
    advance();
  }

  Expression parse() {
    parse_sum();
    if (token_.kind != TokenKind::end) expected("an operator or end of input");
    return Expression(std::move(nodes_), std::move(variables_));
  }

 private:
  // ---- tokens -------------------------------------------------------------------------------
  void advance() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_])))
      ++position_;
    token_ = Token{TokenKind::end, {}, position_ + 1, 0};
    if (position_ == text_.size()) return;
    const char c = text_[position_];
    if (is_digit(c) || c == '.') return take_number();
    if (starts_identifier(c)) return take(TokenKind::identifier, identifier_length());
    if (std::string_view("+-*/^(),").find(c) != std::string_view::npos)
      return take(TokenKind::symbol, 1);
    fail(position_ + 1, fmt::format("unexpected character '{}'", c));
  }

  void take(TokenKind kind, std::size_t length) {
    token_.kind = kind;
    token_.text = text_.substr(position_, length);
    position_ += length;
  }

  std::size_t digits_from(std::size_t at) const {
    std::size_t n = 0;
    while (at + n < text_.size() && is_digit(text_[at + n])) ++n;
    return n;
  }

  std::size_t identifier_length() const {
    std::size_t n = 1;
    while (position_ + n < text_.size() && continues_identifier(text_[position_ + n])) ++n;
    return n;
  }

  // digits [. digits] or . digits, then an optional exponent e[+-]digits.
  void take_number() {
    std::size_t n = digits_from(position_);
    std::size_t digits = n;
    if (position_ + n < text_.size() && text_[position_ + n] == '.') {
      const std::size_t fraction = digits_from(position_ + n + 1);
      n += 1 + fraction;
      digits += fraction;
    }
    if (digits == 0) fail(position_ + 1, "expected a digit before or after '.'");
    n += exponent_length(position_ + n);
    take(TokenKind::number, n);
    token_.value = number_value(token_.text, token_.column);
  }

  std::size_t exponent_length(std::size_t at) const {
    if (at >= text_.size() || (text_[at] != 'e' && text_[at] != 'E')) return 0;
    const std::size_t sign =
        at + 1 < text_.size() && (text_[at + 1] == '+' || text_[at + 1] == '-');
    const std::size_t digits = digits_from(at + 1 + sign);
    return digits == 0 ? 0 : 1 + sign + digits;
  }

  bool at_symbol(char symbol) const {
    return token_.kind == TokenKind::symbol && token_.text.front() == symbol;
  }

  [[noreturn]] void expected(std::string_view what) const {
    fail(token_.column, fmt::format("expected {} but found {}", what, describe(token_)));
  }

  void expect(char symbol) {
    if (!at_symbol(symbol)) expected(fmt::format("'{}'", symbol));
    advance();
  }

  // ---- grammar ------------------------------------------------------------------------------
  void parse_sum() {
    parse_product();
    while (at_symbol('+') || at_symbol('-')) {
      const Op op = at_symbol('+') ? Op::add : Op::sub;
      advance();
      parse_product();
      emit(op);
    }
  }

  void parse_product() {
    parse_unary();
    while (at_symbol('*') || at_symbol('/')) {
      const Op op = at_symbol('*') ? Op::mul : Op::div;
      advance();
      parse_unary();
      emit(op);
    }
  }

  void parse_unary() {
    if (++nesting_ > kMaxNesting)
      fail(token_.column, fmt::format("expression nests deeper than {} levels", kMaxNesting));
    if (at_symbol('-')) {
      advance();
      parse_unary();
      emit(Op::neg);
    } else {
      parse_power();
    }
    --nesting_;
  }

  void parse_power() {
    parse_primary();
    if (!at_symbol('^')) return;
    advance();
    parse_unary();
    emit(Op::pow);
  }

  void parse_primary() {
    if (token_.kind == TokenKind::number) {
      nodes_.push_back(Node{Op::constant, 0, token_.value});
      advance();
    } else if (token_.kind == TokenKind::identifier) {
      parse_identifier();
    } else if (at_symbol('(')) {
      advance();
      parse_sum();
      expect(')');
    } else {
      expected("a number, a variable, a function call or '('");
    }
  }

  void parse_identifier() {
    const Token name = token_;
    advance();
    if (is_fresnel_call(name.text)) return parse_fresnel_call(name);
    const auto function = function_named(name.text);
    if (at_symbol('(') && !function)
      fail(name.column, fmt::format("unknown function '{}'", name.text));
    if (function) return parse_call(name, *function);
    if (name.text == "pi" && std::find(variables_.begin(), variables_.end(), name.text) == variables_.end()) {
      nodes_.push_back(exact_constant(1, 1, Symbol::pi));  // π, unless a variable is called pi
      return;
    }
    nodes_.push_back(Node{Op::variable, variable_index(name), 0});
  }

  void parse_call(const Token& name, Op function) {
    if (!at_symbol('(')) expected(fmt::format("'(' after '{}'", name.text));
    advance();
    int arguments = 1;
    parse_sum();
    while (at_symbol(',')) {
      advance();
      parse_sum();
      ++arguments;
    }
    if (!at_symbol(')')) expected("',' or ')'");
    advance();
    if (arguments != arity(function))
      fail(name.column, fmt::format("'{}' takes {} argument{} but was given {}", name.text,
                                    arity(function), arity(function) == 1 ? "" : "s", arguments));
    emit(function);
  }

  /// A Fresnel call: each argument parsed on its own, then the call's expansion in their place.
  void parse_fresnel_call(const Token& name) {
    if (!at_symbol('(')) expected(fmt::format("'(' after '{}'", name.text));
    std::vector<std::vector<Node>> arguments;
    do {
      advance();
      const std::size_t first = nodes_.size();
      parse_sum();
      arguments.emplace_back(nodes_.begin() + static_cast<std::ptrdiff_t>(first), nodes_.end());
      nodes_.resize(first);
    } while (at_symbol(','));
    if (!at_symbol(')')) expected("',' or ')'");
    advance();
    try {
      const std::vector<Node> expansion = expand_fresnel_call(name.text, arguments);
      nodes_.insert(nodes_.end(), expansion.begin(), expansion.end());
    } catch (const InvalidArgument& e) {
      fail(name.column, e.what());
    }
  }

  std::uint32_t variable_index(const Token& name) {
    const auto found = std::find(variables_.begin(), variables_.end(), name.text);
    if (found != variables_.end()) return static_cast<std::uint32_t>(found - variables_.begin());
    if (fixed_variables_)
      fail(name.column, fmt::format("unknown variable '{}' (the variables are {})", name.text,
                                    fmt::join(variables_, ", ")));
    variables_.emplace_back(name.text);
    return static_cast<std::uint32_t>(variables_.size() - 1);
  }

  void emit(Op op) { nodes_.push_back(Node{op, 0, 0}); }

  std::string_view text_;
  std::vector<std::string> variables_;
  bool fixed_variables_;
  std::vector<Node> nodes_;
  std::size_t position_ = 0;
  Token token_;
  int nesting_ = 0;
};

}  // namespace

ParseError::ParseError(std::size_t column, std::string_view message)
    : InvalidArgument(fmt::format("column {}: {}", column, message)), column_(column), reason_(message) {}

Expression parse(std::string_view text, std::vector<std::string> variables) {
  return Parser(text, std::move(variables)).parse();
}

}  // namespace specula::expr
