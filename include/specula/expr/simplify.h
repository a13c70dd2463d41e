#pragma once
// Algebraic simplification of an Expression (docs/fit.md, "Simplification"): constants folded,
// sums and products flattened, like terms collected (x + a·x → (1 + a)·x), equal factors merged
// into powers (x·x → x², √x·√x → x), x − x, x/x, x·1, x + 0 and double negation removed, and the
// terms and factors put in one canonical order, so that two ways of writing the same formula
// become the same expression. Subtraction and division are written back where a term is negative
// or a factor has a negative power (a + −b prints as a − b).
//
// The rewrites are the algebra of the reals: where they change the domain (x/x → 1 at x = 0,
// √x·√x → x at x < 0) or the rounding, the simplified expression can differ from the original.
// That is what agrees_on() is for: a caller keeps a simplified formula only where it evaluates
// the same on its data. simplify() always terminates: a bounded number of passes, each linear in
// the expression's size up to the sorting of sums and products.
#include <span>
#include <vector>

#include "specula/expr/expr.h"

namespace specula::expr {

/// `e` simplified (same variables, in the same order). `positive[v]` says that variable v is
/// positive wherever the expression is used (a fit's data show it on every row): the rewrites that
/// need a sign then hold — (x^a)^b = x^(a·b), √(x²) = x, log(x^a) = a·log x, exp(a·log x) = x^a,
/// |x| = x, and a sum's common factor leaving a fractional power, (x³ − x)^0.5 = x^0.5·(x² − 1)^0.5.
/// Those that need none always apply: log(exp a) = a, (e^a)^b = e^(a·b).
Expression simplify(const Expression& e, const std::vector<bool>& positive = {});

/// True if a[r] and b[r] agree for every r: |a − b| ≤ tolerance·max(|a|, |b|), or both the same
/// non-finite value.
bool values_agree(std::span<const double> a, std::span<const double> b, double tolerance = 1e-12);

/// True if the two node arrays are the same, constants bit for bit.
bool same_nodes(std::span<const Node> a, std::span<const Node> b);

/// True if `a` and `b` (same variables) evaluate within `tolerance` relative of each other on
/// every row of `columns` (columns[i][r] is variable i in row r): |a − b| ≤ tolerance·max(|a|, |b|)
/// (or both are the same non-finite value). An empty row set agrees.
bool agrees_on(const Expression& a, const Expression& b, std::span<const std::span<const double>> columns,
               double tolerance = 1e-12);

}  // namespace specula::expr
