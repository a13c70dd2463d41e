// The expression ops of the vectorized formula path (src/simd/formula.cpp), once per Highway
// target: each maps vectors to a vector with std::'s IEEE semantics (the special values of
// log(0), exp(inf), pow(−8, 1/3), … as libm gives them) around Highway's contrib math, which
// only covers its valid range. Both lane types; the stated accuracy per op and lane type is in
// include/specula/simd/formula.h, enforced by tests/simd/formula_test.cpp.
//
//   log log2            Highway's Log (and × 1/ln 2); 0 → −inf, +inf → +inf, x < 0 or NaN → NaN
//   exp expm1           Highway's Exp / Expm1 on a clamped argument; overflow → +inf, NaN kept
//   log1p               Highway's Log1p; −1 → −inf, x < −1 → NaN, +inf → +inf
//   sin cos             Highway's for |x| ≤ 39000, std::sin / std::cos per lane beyond (and NaN, inf)
//   acos asin           Highway's on [−1, 1], NaN outside
//   pow                 |a|^b = e^(b ln|a|) (double lanes: ln|a| as a double-double, specula's LnDD)
//                       with C99's special cases; a uniform integer exponent |k| ≤ kMaxPowChain by
//                       multiplication (k = 2: x·x, correctly rounded as libm's pow)

// Per-target include guard (Highway's idiom: toggled once per target).
#if defined(SPECULA_SIMD_FORMULA_OPS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SPECULA_SIMD_FORMULA_OPS_INL_H_
#undef SPECULA_SIMD_FORMULA_OPS_INL_H_
#else
#define SPECULA_SIMD_FORMULA_OPS_INL_H_
#endif

#include <cmath>

#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"
#include "src/simd/kernels-inl.h"

HWY_BEFORE_NAMESPACE();
namespace specula::simd::HWY_NAMESPACE {

/// The largest e^x argument with a finite result, and a floor below which e^x is 0 (or −1).
template <class T>
struct ExpRange;
template <>
struct ExpRange<float> {
  static constexpr float kMax = 88.7228394f;
  static constexpr float kFloor = -110.0f;
};
template <>
struct ExpRange<double> {
  static constexpr double kMax = 709.782712893384;
  static constexpr double kFloor = -1100.0;
};

/// r where 0 < x < inf; std::log's values elsewhere: −inf at ±0, +inf at +inf, NaN below 0.
template <class D>
HWY_INLINE V<D> LogEdges(D d, V<D> x, V<D> r) {
  const auto inside = hn::And(hn::Gt(x, hn::Zero(d)), hn::Lt(x, hn::Inf(d)));
  const V<D> edge = hn::IfThenElse(hn::Eq(x, hn::Zero(d)), hn::Neg(hn::Inf(d)),
                                   hn::IfThenElse(hn::Eq(x, hn::Inf(d)), x, hn::NaN(d)));
  return hn::IfThenElse(inside, r, edge);
}

/// x where 0 < x < inf, 1 elsewhere: Highway's logarithms see only their valid range.
template <class D>
HWY_INLINE V<D> LogArgument(D d, V<D> x) {
  const auto inside = hn::And(hn::Gt(x, hn::Zero(d)), hn::Lt(x, hn::Inf(d)));
  return hn::IfThenElse(inside, x, hn::Set(d, hn::TFromD<D>(1)));
}

template <class D>
HWY_INLINE V<D> LogOp(D d, V<D> x) {
  return LogEdges(d, x, hn::Log(d, LogArgument(d, x)));
}

template <class D>
HWY_INLINE V<D> Log2Op(D d, V<D> x) {
  return LogEdges(d, x, hn::Log2(d, LogArgument(d, x)));
}

/// x clamped to [kFloor, kMax] with NaN lanes at 0: an argument Highway's Exp and Expm1 take.
template <class D>
HWY_INLINE V<D> ExpArgument(D d, V<D> x) {
  using R = ExpRange<hn::TFromD<D>>;
  const V<D> clamped = hn::Min(hn::Max(x, hn::Set(d, R::kFloor)), hn::Set(d, R::kMax));
  return hn::IfThenZeroElse(hn::IsNaN(x), clamped);
}

/// r, with +inf where x > kMax and NaN where x is NaN.
template <class D>
HWY_INLINE V<D> ExpEdges(D d, V<D> x, V<D> r) {
  using R = ExpRange<hn::TFromD<D>>;
  const V<D> big = hn::IfThenElse(hn::Gt(x, hn::Set(d, R::kMax)), hn::Inf(d), r);
  return hn::IfThenElse(hn::IsNaN(x), x, big);
}

/// r, but x itself where x = ±0: the odd functions' sign of zero (sin(−0) = −0).
template <class D>
HWY_INLINE V<D> KeepZero(D d, V<D> x, V<D> r) {
  return hn::IfThenElse(hn::Eq(x, hn::Zero(d)), x, r);
}

template <class D>
HWY_INLINE V<D> ExpOp(D d, V<D> x) {
  return ExpEdges(d, x, hn::Exp(d, ExpArgument(d, x)));
}

template <class D>
HWY_INLINE V<D> Expm1Op(D d, V<D> x) {
  return KeepZero(d, x, ExpEdges(d, x, hn::Expm1(d, ExpArgument(d, x))));
}

template <class D>
HWY_INLINE V<D> Log1pOp(D d, V<D> x) {
  const V<D> minus_one = hn::Set(d, hn::TFromD<D>(-1));
  const auto inside = hn::And(hn::Gt(x, minus_one), hn::Lt(x, hn::Inf(d)));
  const V<D> r = hn::Log1p(d, hn::IfThenElseZero(inside, x));
  const V<D> edge = hn::IfThenElse(hn::Eq(x, minus_one), hn::Neg(hn::Inf(d)),
                                   hn::IfThenElse(hn::Eq(x, hn::Inf(d)), x, hn::NaN(d)));
  return hn::IfThenElse(inside, KeepZero(d, x, r), edge);
}

/// r where `inside`, f(x) per lane (in double) elsewhere.
template <class D, class Scalar>
HWY_INLINE V<D> PerLaneOutside(D d, hn::Mask<D> inside, V<D> x, V<D> r, const Scalar& f) {
  using T = hn::TFromD<D>;
  if (hn::AllTrue(d, inside)) return r;
  HWY_ALIGN T xs[hn::MaxLanes(d)];
  HWY_ALIGN T rs[hn::MaxLanes(d)];
  hn::Store(x, d, xs);
  hn::Store(hn::IfThenElseZero(inside, hn::Set(d, T(1))), d, rs);
  HWY_ALIGN T out[hn::MaxLanes(d)];
  hn::Store(r, d, out);
  for (std::size_t i = 0; i < hn::Lanes(d); ++i)
    if (rs[i] == T(0)) out[i] = static_cast<T>(f(static_cast<double>(xs[i])));
  return hn::Load(d, out);
}

/// Highway's Sin and Cos hold for |x| ≤ 39000.
template <class D>
HWY_INLINE hn::Mask<D> TrigRange(D d, V<D> x) {
  return hn::Le(hn::Abs(x), hn::Set(d, hn::TFromD<D>(39000)));
}

template <class D>
HWY_INLINE V<D> SinOp(D d, V<D> x) {
  const auto inside = TrigRange(d, x);
  const V<D> r = KeepZero(d, x, hn::Sin(d, hn::IfThenElseZero(inside, x)));
  return PerLaneOutside(d, inside, x, r, [](double v) { return std::sin(v); });
}

template <class D>
HWY_INLINE V<D> CosOp(D d, V<D> x) {
  const auto inside = TrigRange(d, x);
  const V<D> r = hn::Cos(d, hn::IfThenElseZero(inside, x));
  return PerLaneOutside(d, inside, x, r, [](double v) { return std::cos(v); });
}

/// Highway's Acos and Asin on [−1, 1]; NaN outside and for NaN.
template <class D>
HWY_INLINE hn::Mask<D> UnitRange(D d, V<D> x) {
  return hn::Le(hn::Abs(x), hn::Set(d, hn::TFromD<D>(1)));
}

template <class D>
HWY_INLINE V<D> AcosOp(D d, V<D> x) {
  const auto inside = UnitRange(d, x);
  return hn::IfThenElse(inside, hn::Acos(d, hn::IfThenElseZero(inside, x)), hn::NaN(d));
}

template <class D>
HWY_INLINE V<D> AsinOp(D d, V<D> x) {
  const auto inside = UnitRange(d, x);
  return hn::IfThenElse(inside, KeepZero(d, x, hn::Asin(d, hn::IfThenElseZero(inside, x))), hn::NaN(d));
}

/// min(a, b) = b < a ? b : a and max(a, b) = a < b ? b : a, as expr::evaluate (NaN order kept).
template <class D>
HWY_INLINE V<D> MinOp(V<D> a, V<D> b) {
  return hn::IfThenElse(hn::Lt(b, a), b, a);
}
template <class D>
HWY_INLINE V<D> MaxOp(V<D> a, V<D> b) {
  return hn::IfThenElse(hn::Lt(a, b), b, a);
}

/// e^(b ln a) for finite a > 0 and finite b, with ln a as a double-double (LnDD) in double lanes
/// (no amplification of ln's rounding by b) and Highway's Log in float lanes.
template <class D>
HWY_INLINE V<D> PowMagnitude(D d, V<D> a, V<D> b) {
  using T = hn::TFromD<D>;
  if constexpr (sizeof(T) == 8) {
    V<D> h, l;
    LnDD(d, a, h, l);
    const V<D> yh = hn::Mul(b, h);
    const V<D> yl = hn::MulAdd(b, l, ProductError(d, b, h, yh));
    const V<D> e = ExpOp(d, yh);  // b·ln a may overflow: then e is 0 or inf and yl is NaN
    return hn::IfThenElse(hn::IsFinite(e), hn::MulAdd(e, hn::IfThenElseZero(hn::IsFinite(yl), yl), e), e);
  } else {
    return ExpOp(d, hn::Mul(b, hn::Log(d, a)));
  }
}

/// pow(a, b) with C99's (and std::pow's) special cases: pow(x, ±0) = pow(1, y) = 1, NaN in NaN
/// out otherwise, a negative finite base with a non-integral exponent NaN, the sign of a
/// negative base to an odd integer kept, zeros and infinities of the base and the exponent as
/// their limits.
template <class D>
HWY_INLINE V<D> PowOp(D d, V<D> a, V<D> b) {
  using T = hn::TFromD<D>;
  const V<D> one = hn::Set(d, T(1)), zero = hn::Zero(d), inf = hn::Inf(d);
  const V<D> ax = hn::Abs(a);
  const auto regular = hn::And(hn::And(hn::Gt(ax, zero), hn::Lt(ax, inf)), hn::IsFinite(b));
  const V<D> magnitude = PowMagnitude(d, hn::IfThenElse(regular, ax, one), hn::IfThenElseZero(regular, b));
  // |a| = 0 or inf, or b = ±inf: 0 or inf as b·ln|a| goes to −inf or +inf.
  const V<D> ln_sign = hn::IfThenElse(hn::Gt(ax, one), one, hn::Neg(one));
  const V<D> limit = hn::IfThenElseZero(hn::Gt(hn::Mul(b, ln_sign), zero), inf);
  const V<D> m = hn::IfThenElse(regular, magnitude, limit);
  const V<D> half_b = hn::Mul(b, hn::Set(d, T(0.5)));
  const auto integral = hn::Eq(hn::Round(b), b);
  const auto odd = hn::And(integral, hn::Ne(hn::Round(half_b), half_b));
  const hn::RebindToSigned<D> di;
  const auto negative_base = hn::RebindMask(d, hn::Lt(hn::BitCast(di, a), hn::Zero(di)));
  V<D> r = hn::IfThenElse(hn::And(negative_base, odd), hn::Neg(m), m);
  const auto complex = hn::And(hn::And(hn::Lt(a, zero), hn::Gt(a, hn::Neg(inf))), hn::Not(integral));
  r = hn::IfThenElse(hn::Or(complex, hn::Or(hn::IsNaN(a), hn::IsNaN(b))), hn::NaN(d), r);
  return hn::IfThenElse(hn::Or(hn::Eq(b, zero), hn::Eq(a, one)), one, r);
}

/// a^k for an integer k by repeated squaring (k < 0: (1/a)^|k|, which underflows gradually where
/// 1/a^|k| would overflow first); k = 2 is a·a and k = −1 is 1/a, correctly rounded.
template <class D>
HWY_INLINE V<D> PowInteger(D d, V<D> a, int k) {
  using T = hn::TFromD<D>;
  V<D> result = hn::Set(d, T(1)), square = k < 0 ? hn::Div(hn::Set(d, T(1)), a) : a;
  bool started = false;
  for (unsigned e = static_cast<unsigned>(k < 0 ? -k : k); e != 0; e >>= 1) {
    if (e & 1u) {
      result = started ? hn::Mul(result, square) : square;
      started = true;
    }
    if (e > 1) square = hn::Mul(square, square);
  }
  return result;
}

}  // namespace specula::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // SPECULA_SIMD_FORMULA_OPS_INL_H_
