#pragma once
// Expressions shared by symbolic regression, code generation and user-defined lobes.
// An Expression is a postfix (RPN) array of nodes over named variables: compact to copy, cheap to
// mutate, and evaluated by a stack machine. parse() reads infix text:
//   numbers 2, 0.5, .5, 1e-3, 2.5E+7   pi   variables (identifiers)   + - * / ^   unary -   ( )
//   log log2 exp sqrt abs sin cos acos expm1 log1p asin (one argument)   pow min max (two arguments)
//   the Fresnel calls, which parse() expands into those ops (fresnel_call below)
// ^ is right-associative and binds tighter than unary minus (-2^2 = -4, 2^-1 = 0.5). Function names
// are reserved. Evaluation follows IEEE semantics (x/0 is ±inf or nan, nothing throws);
// min(a, b) = b < a ? b : a and max(a, b) = a < b ? b : a, exactly std::min / std::max.
// Printers: to_infix (canonical, parse(to_infix(e)) evaluates bit-identically to e), to_cpp,
// to_glsl (floats), to_latex, to_python (Python raises where IEEE gives inf/nan, e.g. 1 / 0).
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "specula/exceptions.h"

namespace specula::expr {

enum class Op : std::uint8_t {
  constant, variable,                            // leaves
  add, sub, mul, div, pow, min, max,             // two operands
  neg, log, log2, exp, sqrt, abs, sin, cos, acos,  // one operand
  expm1, log1p, asin                              // one operand: e^x − 1 and ln(1 + x) exact near 0
};

/// How many ops there are: a table indexed by Op has exactly this many entries (`asin` is the last
/// op; an op added after it moves this count).
inline constexpr std::size_t kOpCount = static_cast<std::size_t>(Op::asin) + 1;

/// The number an exact constant is a rational multiple of (constant snapping, docs/fit.md).
enum class Symbol : std::uint8_t { one, pi, e, ln2, sqrt2, sqrt3 };
inline constexpr std::size_t kSymbolCount = static_cast<std::size_t>(Symbol::sqrt3) + 1;  // sqrt3: the last

struct Node {
  Op op = Op::constant;
  std::uint32_t var = 0;  // Op::variable: index into Expression::variables()
  double value = 0;       // Op::constant
  /// Op::constant, when it is exact: value = numerator · symbol / denominator, printed so ("1 / 3",
  /// "3 * pi / 4"); denominator 0 for a plain number. A fit holds exact constants fixed.
  std::int16_t numerator = 0;
  std::uint8_t denominator = 0;
  Symbol symbol = Symbol::one;
};

/// The value of a symbol as the printed text computes it (pi and e as std::numbers has them,
/// log(2), sqrt(2), sqrt(3) as std::log and std::sqrt).
double symbol_value(Symbol symbol);

/// The exact constant numerator · symbol / denominator (denominator ≥ 1), its value computed as
/// its text reads: (numerator · symbol) / denominator.
Node exact_constant(int numerator, int denominator, Symbol symbol);

/// True for an exact constant.
inline bool is_exact(const Node& node) { return node.op == Op::constant && node.denominator > 0; }

/// Per node of a postfix array: whether the subtree it roots is built of exact constants only — an
/// exact constant, or an op over such (an elementary constant: exp(−1/2), 1/√(2π)).
std::vector<bool> exact_only_subtrees(std::span<const Node> nodes);

/// Operands an op takes: 0 for leaves, 1 or 2 otherwise.
int arity(Op op);

/// The call name of a function op ("log", "pow", …); empty for operators and leaves.
std::string_view function_name(Op op);

/// The op a call name denotes, if any.
std::optional<Op> function_named(std::string_view name);

/// The Fresnel reflectance at the cosine c as calls that parse() expands into the ops above
/// (docs/fresnel.md, "In a formula"), so that every printer, the SIMD path and the shaders read
/// them as any formula:
///   fresnel_schlick(c, f0)             F0 + (1 − F0)(1 − c)⁵
///   fresnel_schlick(c, f0, f90, p)     F0 + (F90 − F0)(1 − c)^p
///   fresnel_f82(c, f0, tint)           Hoffman's F82-tint, clamped to [0, 1]
///   fresnel_dielectric(c, eta)         the exact dielectric, η = n_t/n_i, total internal reflection
///   fresnel_conductor(c, eta, kappa)   the exact conductor, index η + iκ (real arithmetic)
/// True for their names, which are reserved as function names are.
bool is_fresnel_call(std::string_view name);

/// True for a name a variable, parameter or let may not take: a function's or a Fresnel call's.
inline bool is_reserved_call(std::string_view name) { return function_named(name) || is_fresnel_call(name); }

class Expression {
 public:
  /// Throws InvalidArgument unless `nodes` is a well-formed postfix expression: no operand
  /// missing, exactly one result, finite constants, variable indices in range, and `variables`
  /// distinct identifiers that are not function names.
  Expression(std::vector<Node> nodes, std::vector<std::string> variables);

  std::span<const Node> nodes() const { return nodes_; }
  const std::vector<std::string>& variables() const { return variables_; }
  std::size_t size() const { return nodes_.size(); }
  /// The most values the evaluation stack holds at once.
  std::size_t stack_depth() const { return stack_depth_; }

 private:
  std::vector<Node> nodes_;
  std::vector<std::string> variables_;
  std::size_t stack_depth_ = 0;
};

/// A syntax error; the message reads "column N: …" (1-based).
class ParseError : public InvalidArgument {
 public:
  ParseError(std::size_t column, std::string_view message);
  /// The column (1-based) of the text where the error is.
  std::size_t column() const noexcept { return column_; }
  /// The message without its "column N: " prefix.
  const std::string& reason() const noexcept { return reason_; }

 private:
  std::size_t column_;
  std::string reason_;
};

/// With `variables` given, the expression has exactly those variables (in that order) and other
/// identifiers are errors; otherwise its variables are the identifiers in order of first use.
/// `pi` is the exact constant π unless `variables` has a variable called pi.
Expression parse(std::string_view text, std::vector<std::string> variables = {});

/// The postfix nodes of the Fresnel call `name` (is_fresnel_call) with `arguments`, each the nodes
/// of one argument: its definition with the arguments in place of its variables. Throws
/// InvalidArgument naming the call and the counts it takes when their number is wrong.
std::vector<Node> expand_fresnel_call(std::string_view name, std::span<const std::vector<Node>> arguments);

/// Parsing nests at most this deep (parentheses, unary minus, exponents).
inline constexpr int kMaxNesting = 1000;

std::string to_infix(const Expression& e);
std::string to_cpp(const Expression& e);
std::string to_glsl(const Expression& e);
std::string to_latex(const Expression& e);
std::string to_python(const Expression& e);

/// `variables[i]` is the value of e.variables()[i]; throws InvalidArgument if too few are given.
double evaluate(const Expression& e, std::span<const double> variables);

/// One operation (not a leaf) on its operands as evaluate() computes it; b unused by a unary one.
double apply(Op op, double a, double b = 0);

/// out[r] = evaluate(e, row r), where columns[i][r] is variable i in row r. Works through the rows
/// in chunks, one whole chunk per node. Throws InvalidArgument if a column is missing or its
/// length differs from out.size().
void evaluate_batch(const Expression& e, std::span<const std::span<const double>> columns,
                    std::span<double> out);

}  // namespace specula::expr
