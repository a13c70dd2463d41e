#pragma once
// Constants and arithmetic as a GPU sees them (docs/designer.md, "Precision"): a member's
// per-pixel constants rounded to float32 or binary16 and then moved one unit in the last place at
// a time while that lowers its largest error (as SLEEF's coefficient generator does), its
// arithmetic evaluated in that precision (the inputs and every operation's result rounded to it;
// the parameter's subexpressions — a material's uniforms — computed in double and rounded once),
// and its error measured again.
#include <span>
#include <string>
#include <vector>

#include "fitting.h"
#include "specula/design/design.h"

namespace specula::design {

/// x rounded to the nearest value of `precision`, ties to even (binary16: 11 significant bits,
/// subnormals in steps of 2⁻²⁴, ±inf past 65504; double: x itself).
double round_to(double x, Precision precision);

/// The value of `precision` next to x (a value of it) toward +inf (direction > 0) or −inf.
double next_in(double x, int direction, Precision precision);

/// `e` (variables: the per-pixel ones, then the range parameter if any) evaluated in `precision`.
/// One evaluator per thread: it keeps its stack between calls.
class RoundedEvaluator {
 public:
  RoundedEvaluator(const expr::Expression& e, std::size_t per_pixel_variables, Precision precision);
  double operator()(std::span<const double> point) const;
  /// The fitted numbers a shader carries as literals (node indices): plain constants that are not
  /// integers, not a power's exponent, and not inside the parameter's subexpressions.
  std::vector<std::size_t> literals() const;
  /// Literal `node`'s value, and a new one for it (the structure, and so the literals, stay).
  double literal(std::size_t node) const { return nodes_[node].value; }
  void set_literal(std::size_t node, double value) { nodes_[node].value = value; }
  /// The expression with the literals as they are now.
  expr::Expression expression() const { return expr::Expression(nodes_, variables_); }

 private:
  std::vector<expr::Node> nodes_;
  std::vector<std::string> variables_;
  std::vector<bool> round_here_;  // per node: rounded after it (all but a uniform's inner nodes)
  std::vector<bool> literal_;     // per node: a fitted number outside the uniforms
  Precision precision_;
  mutable std::vector<double> stack_;
};

/// Member l rounded to s.precision (not f64): its literals rounded, then each moved one ulp at a
/// time (at most 16 a pass, 4 passes) while the largest error on `rows` (the fits' rows at the
/// fine grid's parameter values), arithmetic in that precision, goes down. l.formula gets those
/// constants; l.precision_error is that largest error; l.precision_note is set when it is past
/// `claim` (the member's error before rounding). The caller measures l's error again.
void round_member(Lobe& l, std::span<const Samples> rows, const Settings& s, double claim);

}  // namespace specula::design
