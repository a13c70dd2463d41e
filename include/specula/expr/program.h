#pragma once
// A formula with named intermediate terms, as a paper writes one: `let` steps ("D = …", "G = …"),
// each usable after it is defined, then a result. Every expression reads from one array of slots:
// the inputs, then the parameters, then the lets in order, so evaluation is a loop over the steps
// that writes each let into its slot. User-defined models (catalogue/model_file.h) are programs.
//
// The names `pi` and `e` are constants; an input, parameter or let may not be called so.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "specula/expr/expr.h"

namespace specula::expr {

/// The most slots (inputs + parameters + lets) a program has, and the longest formula text.
inline constexpr std::size_t kMaxSlots = 64;
inline constexpr std::size_t kMaxFormulaLength = 4096;
/// The deepest evaluation stack a formula may need (nesting of parentheses and operators).
inline constexpr std::size_t kMaxFormulaDepth = 64;

class Program {
 public:
  /// A program over `inputs` then `params` (distinct identifiers, none reserved). Throws
  /// InvalidArgument naming a bad or repeated name.
  Program(std::vector<std::string> inputs, std::vector<std::string> params);

  /// Appends the step `name = text`. Throws ParseError ("column N: …", N within `text`) for a
  /// syntax error or an unknown identifier, and InvalidArgument for a bad or repeated name, a
  /// text over kMaxFormulaLength or a formula deeper than kMaxFormulaDepth.
  void let(std::string name, std::string_view text);
  /// Sets the result, once (the same errors as let()).
  void set_result(std::string_view text);

  std::span<const std::string> slot_names() const noexcept { return slots_; }
  std::size_t input_count() const noexcept { return inputs_; }
  std::size_t param_count() const noexcept { return params_; }
  /// The let steps, in order; lets()[i] writes slot input_count() + param_count() + i.
  std::span<const Expression> lets() const noexcept { return lets_; }
  const Expression& result() const noexcept { return result_; }
  bool has_result() const noexcept { return has_result_; }
  /// True if a step reads slot `slot` (e.g. whether a lobe's formula uses c or u).
  bool reads(std::size_t slot) const noexcept;

  /// Evaluates with slots[0, input_count() + param_count()) set; fills the let slots.
  /// `slots` has slot_names().size() values.
  double evaluate(std::span<double> slots) const noexcept;

  /// out[r] = evaluate() of row r, where inputs[i][r] is input i and `params` the parameters (in
  /// order), bit-identical to evaluate(): each step through expr::evaluate_batch, a chunk of rows
  /// at a time. Precondition: input_count() inputs and param_count() params, each input column
  /// as long as out.
  void evaluate_batch(std::span<const std::span<const double>> inputs, std::span<const double> params,
                      std::span<double> out) const;
  /// The nodes of every step: the work of one evaluation.
  std::size_t node_count() const noexcept;

 private:
  Expression parse_step(std::string_view text) const;
  void note_reads(const Expression& e);

  std::vector<std::string> slots_;
  std::size_t inputs_ = 0;
  std::size_t params_ = 0;
  std::vector<Expression> lets_;
  Expression result_{{Node{}}, {}};
  bool has_result_ = false;
  std::vector<bool> reads_;
};

/// Checks that `name` may name an input, parameter or let: an identifier, not a function name and
/// not a constant. Throws InvalidArgument naming `what` ("parameter", "let") otherwise.
void require_slot_name(std::string_view name, std::string_view what);

/// evaluate(e, slots) without the size check (the caller guarantees it): the program's inner loop.
double evaluate_unchecked(const Expression& e, std::span<const double> slots) noexcept;

}  // namespace specula::expr
