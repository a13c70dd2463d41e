// Element-wise column arithmetic (columns.h), per Highway target.
#include <cstddef>

#include "columns.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/expr/columns.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace specula::expr::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <class Op>
void Binary(double* HWY_RESTRICT a, const double* HWY_RESTRICT b, std::size_t n, const Op& op) {
  const hn::ScalableTag<double> d;
  const hn::CappedTag<double, 1> d1;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) hn::StoreU(op(hn::LoadU(d, a + i), hn::LoadU(d, b + i)), d, a + i);
  for (; i < n; ++i) hn::StoreU(op(hn::LoadU(d1, a + i), hn::LoadU(d1, b + i)), d1, a + i);
}

template <class Op>
void Unary(double* HWY_RESTRICT a, std::size_t n, const Op& op) {
  const hn::ScalableTag<double> d;
  const hn::CappedTag<double, 1> d1;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + lanes <= n; i += lanes) hn::StoreU(op(hn::LoadU(d, a + i)), d, a + i);
  for (; i < n; ++i) hn::StoreU(op(hn::LoadU(d1, a + i)), d1, a + i);
}

void ApplyColumns(ColumnOp op, double* a, const double* b, std::size_t n) {
  switch (op) {
    case ColumnOp::add: return Binary(a, b, n, [](auto x, auto y) { return hn::Add(x, y); });
    case ColumnOp::sub: return Binary(a, b, n, [](auto x, auto y) { return hn::Sub(x, y); });
    case ColumnOp::mul: return Binary(a, b, n, [](auto x, auto y) { return hn::Mul(x, y); });
    case ColumnOp::div: return Binary(a, b, n, [](auto x, auto y) { return hn::Div(x, y); });
    case ColumnOp::min: return Binary(a, b, n, [](auto x, auto y) { return hn::IfThenElse(hn::Lt(y, x), y, x); });
    case ColumnOp::max: return Binary(a, b, n, [](auto x, auto y) { return hn::IfThenElse(hn::Lt(x, y), y, x); });
    case ColumnOp::neg: return Unary(a, n, [](auto x) { return hn::Neg(x); });
    case ColumnOp::sqrt: return Unary(a, n, [](auto x) { return hn::Sqrt(x); });
    case ColumnOp::abs: return Unary(a, n, [](auto x) { return hn::Abs(x); });
  }
}

}  // namespace specula::expr::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace specula::expr {

HWY_EXPORT(ApplyColumns);

void apply_columns(ColumnOp op, double* a, const double* b, std::size_t n) noexcept {
  HWY_DYNAMIC_DISPATCH(ApplyColumns)(op, a, b, n);
}

}  // namespace specula::expr
#endif
