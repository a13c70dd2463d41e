#pragma once
// A lobe written as a formula (a user-defined model, catalogue/model_file.h): F(c) in the cosine c,
// or F(u) in u = −ln c, or both (docs/models.md). The formula in u keeps very narrow lobes exact
// (1 − c underflows where u does not), as the built-in lobes' at_log_cos do.
//
// What a built-in lobe states by hand, a Formula finds numerically when it is made: its support
// end (the u beyond which F = 0), its half-maximum, and its kinks (the points where an argument
// of min, max or abs changes sign), each located by bisection to a few ulp on a grid of 2000 u
// from 1e-20 to 64 (c from 1 − 1e-20 to 1.6e-28). Kinks or zero crossings closer together than
// the grid's 2.5 % spacing may be missed; the analysis integrals split at every kink found.
//
// Conventions as every lobe (lobes/lobe.h): F = 0 for c ≤ 0, c clamped to 1; nothing throws.
#include <array>
#include <memory>
#include <string_view>
#include <span>
#include <vector>

#include "specula/expr/program.h"
#include "specula/lobes/lobe.h"

namespace specula::lobes {

/// The formulas of a lobe, shared by every Formula made from them. Both have the inputs
/// kInputs (c and u = −ln c; a formula may use either or both) and the same parameters; at least
/// one is set. F(c) uses `in_cos` if set, F at u uses `in_log_cos` if set, each the other if not.
struct FormulaDefinition {
  static constexpr std::array<std::string_view, 2> kInputs{"c", "u"};

  std::shared_ptr<const expr::Program> in_cos;
  std::shared_ptr<const expr::Program> in_log_cos;

  const expr::Program& any() const noexcept { return in_log_cos ? *in_log_cos : *in_cos; }
};

class Formula {
 public:
  /// The lobe at parameter values `params` (in the programs' parameter order). Throws
  /// InvalidArgument if the count differs.
  Formula(std::shared_ptr<const FormulaDefinition> definition, std::vector<double> params);

  double operator()(double c) const noexcept;
  double at_log_cos(double u) const noexcept;
  double half_max_log_cos() const noexcept { return half_max_; }
  double support_log_cos() const noexcept { return support_; }
  /// out[i] = F(c[i]) for i < min(c.size(), out.size()), bit-identical to operator() (through
  /// expr::Program::evaluate_batch).
  void eval_batch(std::span<const double> c, std::span<double> out) const;
  /// The kinks found in (0, support), ascending.
  std::span<const double> kinks_log_cos() const noexcept { return kinks_; }

  const FormulaDefinition& definition() const noexcept { return *definition_; }
  std::span<const double> params() const noexcept { return params_; }

 private:
  /// The program at (c, u); `c_of_u` says which of them to derive from the other if read.
  double run(const expr::Program& program, double c, double u, bool c_of_u) const noexcept;

  std::shared_ptr<const FormulaDefinition> definition_;
  std::vector<double> params_;
  double half_max_ = 1;
  double support_ = kInfinity<double>;
  std::vector<double> kinks_;
};

/// The kinks of a lobe in u: a Formula's, none for the built-in families (their only kink is the
/// support end, which every integral already ends at).
template <class L>
std::span<const double> kinks_log_cos(const L& lobe) noexcept {
  if constexpr (requires { lobe.kinks_log_cos(); }) return lobe.kinks_log_cos();
  else return {};
}

}  // namespace specula::lobes
