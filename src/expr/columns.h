#pragma once
// Private to expr.
// Element-wise arithmetic over columns of doubles with Highway's dispatched vectors: the
// correctly rounded IEEE operations, so results are bit-identical to the scalar loop's
// (a + b, a − b, a·b, a/b, √a, |a|, −a each round once, on every target). min and max follow
// expr's definitions, min(a, b) = b < a ? b : a and max(a, b) = a < b ? b : a, NaN and signed
// zeros included. Used by expr::evaluate_batch, the fit's evaluator.
#include <cstddef>

namespace specula::expr {

enum class ColumnOp { add, sub, mul, div, min, max, neg, sqrt, abs };

/// a[i] = a[i] op b[i] for i < n (binary ops); a[i] = op a[i] for neg, sqrt and abs (b unused).
void apply_columns(ColumnOp op, double* a, const double* b, std::size_t n) noexcept;

}  // namespace specula::expr
