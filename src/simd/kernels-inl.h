// The SIMD lobe kernels, once per Highway target (included by src/simd/*.cpp through
// hwy/foreach_target.h). Each kernel maps a vector of cosines to a vector of F(c); the stated
// bounds are in include/specula/simd/lobes.h, the polynomials in poly_coefficients.h.
//
// Building blocks (docs/math.md §3 for the log lobe's t-space):
//   SplitExponent   c = 2^e (1 + x), 1 + x ∈ [√½, √2), x exact; subnormal c included
//   Log2Fast        log2 c to ~1 ulp of float: e + x·P₈(x), P's leading term split hi + lo
//   Exp2Fast        2^y = 2^k (1 + f·P₄(f)), k = round(y), f = y − k ∈ [−½, ½]
//   Log1pShort/Plain ln(1 + x) for x ∈ [√½ − 1, √2 − 1]: 2 atanh(z) = 2z + z³Q(z²), z = x/(2 + x)
//   Log1pDD         the same as hi + lo, z carried as hi + lo through the quotient's remainder
//   LnDD            ln c = e·ln2 + ln(1 + x) as hi + lo (double only)
// Exact kernels work in double lanes: double-double logarithms for double arrays; for float
// arrays the logarithms in double and, for c^n and Gauss, the exponential in float lanes
// (Exp2InFloatLanes) or the whole kernel promoted (the log lobe); the double Gauss kernel calls
// Highway's contrib Acos and Exp (max error 2 and 1 ULP, hwy/contrib/math/math-inl.h). Fast
// kernels work in the lane type with the short polynomials. Each kernel states its op count
// (kOps: vector instructions per vector, loads and stores of the arrays not counted) for the
// benchmark's compute limit.
//
// NaN: every kernel returns what the scalar lobe returns for NaN: NaN, except gauss (0, since
// the scalar tests c > 0).

// Per-target include guard (Highway's idiom: toggled once per target).
#if defined(SPECULA_SIMD_KERNELS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SPECULA_SIMD_KERNELS_INL_H_
#undef SPECULA_SIMD_KERNELS_INL_H_
#else
#define SPECULA_SIMD_KERNELS_INL_H_
#endif

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <utility>

#include "hwy/contrib/math/math-inl.h"
#include "hwy/highway.h"
#include "src/simd/poly_coefficients.h"

HWY_BEFORE_NAMESPACE();
namespace specula::simd::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

template <class D>
using V = hn::VFromD<D>;

// ---------------------------------------------------------------------------------------------
// Polynomials and constants

/// c[first] + c[first+1] x + … by Horner's rule, coefficients rounded to the lane type.
template <std::size_t first = 0, class D, std::size_t N>
HWY_INLINE V<D> Horner(D d, V<D> x, const std::array<double, N>& c) {
  using T = hn::TFromD<D>;
  V<D> r = hn::Set(d, static_cast<T>(c[N - 1]));
  for (std::size_t i = N - 1; i-- > first;) r = hn::MulAdd(r, x, hn::Set(d, static_cast<T>(c[i])));
  return r;
}

/// The same polynomial by Estrin's scheme (Highway's impl::Estrin): a few more multiplications,
/// a dependency chain of log₂ N instead of N FMAs — for the long polynomials of the exact tier,
/// whose kernels are bound by latency as much as by throughput.
template <std::size_t first, class D, std::size_t N, std::size_t... I>
HWY_INLINE V<D> EstrinOf(D d, V<D> x, const std::array<double, N>& c, std::index_sequence<I...>) {
  using T = hn::TFromD<D>;
  return hn::impl::Estrin(x, hn::Set(d, static_cast<T>(c[first + I]))...);
}
template <std::size_t first = 0, class D, std::size_t N>
HWY_INLINE V<D> Estrin(D d, V<D> x, const std::array<double, N>& c) {
  return EstrinOf<first>(d, x, c, std::make_index_sequence<N - first>());
}

template <class T>
struct Bits;
template <>
struct Bits<float> {
  using Int = int32_t;
  static constexpr int kMantissa = 23;
  static constexpr Int kBias = 127;
  static constexpr Int kSqrtHalf = 0x3F3504F3;  // the float nearest √½
  static constexpr Int kOne = 0x3F800000;
  static constexpr Int kMantissaMask = 0x007FFFFF;
  static constexpr float kMinExp2 = -125.5f;  // 2^y stays normal for y ≥ this (Exp2Fast)
};
template <>
struct Bits<double> {
  using Int = int64_t;
  static constexpr int kMantissa = 52;
  static constexpr Int kBias = 1023;
  static constexpr Int kSqrtHalf = 0x3FE6A09E667F3BCD;
  static constexpr Int kOne = 0x3FF0000000000000;
  static constexpr Int kMantissaMask = 0x000FFFFFFFFFFFFF;
  static constexpr double kMinExp2 = -1021.5;
};

/// 2^k for an integral k, exactly (k ≤ 127 or 1023).
template <class T>
constexpr T pow2(int k) {
  T r = 1;
  for (; k > 0; --k) r *= 2;
  for (; k < 0; ++k) r /= 2;
  return r;
}

// ---------------------------------------------------------------------------------------------
// Logarithm and exponential building blocks

/// c = 2^e (1 + x) with 1 + x ∈ [√½, √2): x = m − 1 is exact (Sterbenz). c > 0 and finite;
/// subnormal c are scaled by 2^(mantissa + 2) first. Other lanes give finite garbage.
/// kSubnormals = false skips that (float inputs promoted to double are never subnormal).
template <bool kSubnormals = true, class D>
HWY_INLINE void SplitExponent(D d, V<D> c, V<D>& x, V<D>& e) {
  using T = hn::TFromD<D>;
  using B = Bits<T>;
  const hn::RebindToSigned<D> di;
  constexpr int kScale = B::kMantissa + 2;
  const auto tiny = hn::Lt(c, hn::Set(d, std::numeric_limits<T>::min()));
  if constexpr (kSubnormals) c = hn::IfThenElse(tiny, hn::Mul(c, hn::Set(d, pow2<T>(kScale))), c);
  // Adding 1 − √½ in bit space moves the exponent step from c = 1 to c = √½.
  const auto shifted = hn::Add(hn::BitCast(di, c), hn::Set(di, B::kOne - B::kSqrtHalf));
  const auto ei = hn::Sub(hn::ShiftRight<B::kMantissa>(shifted), hn::Set(di, B::kBias));
  const auto m = hn::Add(hn::And(shifted, hn::Set(di, B::kMantissaMask)), hn::Set(di, B::kSqrtHalf));
  x = hn::Sub(hn::BitCast(d, m), hn::Set(d, T(1)));
  e = hn::ConvertTo(d, ei);
  if constexpr (kSubnormals) e = hn::Sub(e, hn::IfThenElseZero(tiny, hn::Set(d, T(kScale))));
}

/// log2 c for c > 0 (finite garbage elsewhere): e + x·P₈(x). P's leading coefficient is split
/// into T(c₀) + the rest so that the term that dominates rounds once, in the final FMA: within
/// ~1.3 ulp of float (polynomial 2.98e-8 relative, poly_coefficients.h). Log2FastReduced is
/// log2(1 + x) for x ∈ [√½ − 1, √2 − 1].
template <class D>
HWY_INLINE V<D> Log2FastReduced(D d, V<D> x) {
  using T = hn::TFromD<D>;
  constexpr double c0 = poly::kLog2p1Deg8[0];
  constexpr T c0_hi = static_cast<T>(c0);
  constexpr T c0_lo = static_cast<T>(c0 - static_cast<double>(c0_hi));
  const V<D> rest = hn::MulAdd(x, Horner<1>(d, x, poly::kLog2p1Deg8), hn::Set(d, c0_lo));
  return hn::MulAdd(x, hn::Set(d, c0_hi), hn::Mul(x, rest));
}

template <class D>
HWY_INLINE V<D> Log2Fast(D d, V<D> c) {
  V<D> x, e;
  SplitExponent(d, c, x, e);
  return hn::Add(e, Log2FastReduced(d, x));
}

/// 2^y for y ≥ Bits<T>::kMinExp2 (normal results): 2^k (1 + f·P₄(f)), relative error ≤ 3.5e-7
/// plus rounding. Lanes below kMinExp2 give garbage: the caller zeroes them.
/// Exp2Poly is the same with another polynomial for (2^f − 1)/f.
/// 2^(k + f) = 2^k (1 + f·P(f)) for integral k ≥ Bits<T>::kMinExp2 + ½ and |f| ≤ ~½.
template <class D, std::size_t N>
HWY_INLINE V<D> Exp2Reduced(D d, V<D> f, V<D> k, const std::array<double, N>& coefficients) {
  using T = hn::TFromD<D>;
  const hn::RebindToSigned<D> di;
  const V<D> poly = N >= 8 ? Estrin(d, f, coefficients) : Horner(d, f, coefficients);
  const V<D> p = hn::MulAdd(f, poly, hn::Set(d, T(1)));
  const auto scale = hn::ShiftLeft<Bits<T>::kMantissa>(hn::ConvertTo(di, k));
  return hn::BitCast(d, hn::Add(hn::BitCast(di, p), scale));
}

template <class D, std::size_t N>
HWY_INLINE V<D> Exp2Poly(D d, V<D> y, const std::array<double, N>& coefficients) {
  const V<D> k = hn::Round(y);
  return Exp2Reduced(d, hn::Sub(y, k), k, coefficients);
}

template <class D>
HWY_INLINE V<D> Exp2Fast(D d, V<D> y) {
  return Exp2Poly(d, y, poly::kExp2m1Deg4);
}

/// a·b − p, exact when p = RN(a·b): one FMA, or Dekker's product on targets without FMA
/// (SSSE3, SSE4, EMU128, SCALAR), where MulAdd rounds twice.
template <class D>
HWY_INLINE V<D> ProductError(D d, V<D> a, V<D> b, V<D> p) {
#if HWY_NATIVE_FMA
  (void)d;
  return hn::MulSub(a, b, p);
#else
  using T = hn::TFromD<D>;
  const V<D> k = hn::Set(d, sizeof(T) == 8 ? T(134217729.0) : T(4097.0));  // Veltkamp: 2^⌈p/2⌉ + 1
  auto split = [&](V<D> v, V<D>& hi, V<D>& lo) {
    const V<D> g = hn::Mul(k, v);
    hi = hn::Sub(g, hn::Sub(g, v));
    lo = hn::Sub(v, hi);
  };
  V<D> ah, al, bh, bl;
  split(a, ah, al);
  split(b, bh, bl);
  const V<D> e = hn::Add(hn::Sub(hn::Mul(ah, bh), p), hn::Mul(ah, bl));
  return hn::Add(hn::Add(e, hn::Mul(al, bh)), hn::Mul(al, bl));
#endif
}

/// c − a·b to ~2⁻¹⁰⁵ relative when a·b ≈ c (the remainder of a quotient c/b ≈ a).
template <class D>
HWY_INLINE V<D> Remainder(D d, V<D> a, V<D> b, V<D> c) {
#if HWY_NATIVE_FMA
  (void)d;
  return hn::NegMulAdd(a, b, c);
#else
  const V<D> p = hn::Mul(a, b);
  return hn::Sub(hn::Sub(c, p), ProductError(d, a, b, p));
#endif
}

/// Reciprocal to ~2⁻²² (float: one Newton step on the 12- or 14-bit estimate); double divides.
template <class D>
HWY_INLINE V<D> ReciprocalFast(D d, V<D> x) {
  using T = hn::TFromD<D>;
  if constexpr (sizeof(T) == 4) {
    const V<D> r = hn::ApproximateReciprocal(x);
    return hn::Mul(r, hn::NegMulAdd(x, r, hn::Set(d, T(2))));
  } else {
    return hn::Div(hn::Set(d, T(1)), x);
  }
}

/// ln(1 + x) = hi + lo for x ∈ [√½ − 1, √2 − 1] (x exact), in double lanes:
/// ln((1 + z)/(1 − z)) = 2z + (2/3)z³ + z⁵P(w), w = z², z = x/(2 + x) carried as
/// z + zl (the remainder of the quotient), (2/3)z³ as a double-double, and the rest (≤ 2e-4 of
/// the sum) in double: |hi + lo − ln(1 + x)| ≤ ~3e-20 |ln(1 + x)|.
template <class D>
HWY_INLINE void Log1pDD(D d, V<D> x, V<D>& hi, V<D>& lo) {
  using T = hn::TFromD<D>;
  static_assert(sizeof(T) == 8, "Log1pDD works in double lanes");
  const V<D> one = hn::Set(d, 1.0), two = hn::Set(d, 2.0);
  const V<D> s = hn::Add(two, x);
  const V<D> s_lo = hn::Add(hn::Sub(two, s), x);  // 2 + x = s + s_lo exactly (|2| ≥ |x|)
  const V<D> inv = hn::Div(one, s);
  const V<D> z = hn::Mul(x, inv);
  V<D> r = Remainder(d, z, s, x);
  r = hn::NegMulAdd(z, s_lo, r);
  const V<D> zl = hn::Mul(r, inv);
  // z³ = z3 + z3l, then (2/3)z³ = c3 + c3l with 2/3 = 0.666… + 3.7e-17.
  const V<D> w = hn::Mul(z, z);
  const V<D> z3 = hn::Mul(z, w);
  const V<D> two_thirds = hn::Set(d, 0.66666666666666663), two_thirds_lo = hn::Set(d, 3.700743415417188e-17);
  const V<D> c3 = hn::Mul(two_thirds, z3);
  const V<D> wl = ProductError(d, z, z, w);
  const V<D> z3l = hn::MulAdd(z, wl, ProductError(d, z, w, z3));
  const V<D> c3l = hn::MulAdd(two_thirds_lo, z3, hn::MulAdd(two_thirds, z3l, ProductError(d, two_thirds, z3, c3)));
  // z⁵P(w), plus the first-order effect of zl on (2/3)z³ (2 w zl) and on 2z (2 zl).
  const V<D> rest = hn::MulAdd(hn::Mul(z3, w), Estrin(d, w, poly::kAtanhTailDeg6), hn::Mul(hn::MulAdd(w, two, two), zl));
  const V<D> twoz = hn::Add(z, z);
  hi = hn::Add(twoz, c3);
  lo = hn::Add(hn::Add(hn::Sub(twoz, hi), c3), hn::Add(c3l, rest));  // |2z| ≥ |c3|
}

/// 2z + z³(2/3 + w·Q(w)), z = x/(2 + x), w = z²: ln(1 + x) = 2 atanh(z), with `tail` giving Q(w).
template <class D, class Tail>
HWY_INLINE V<D> Log1pAtanh(D d, V<D> x, const Tail& tail) {
  const V<D> z = hn::Div(x, hn::Add(hn::Set(d, 2.0), x));
  const V<D> w = hn::Mul(z, z);
  const V<D> q = hn::MulAdd(w, tail(w), hn::Set(d, 2.0 / 3.0));
  return hn::MulAdd(hn::Mul(z, w), q, hn::Add(z, z));
}

/// ln(1 + x) for x ∈ [√½ − 1, √2 − 1] to ~1e-13 relative: Q = P₃ by Horner's rule.
/// Double lanes; the float exact tier, whose result is rounded to float once.
template <class D>
HWY_INLINE V<D> Log1pShort(D d, V<D> x) {
  return Log1pAtanh(d, x, [d](V<D> w) { return Horner(d, w, poly::kAtanhTailDeg3); });
}

/// ln(1 + x) to ~1.5 ulp relative for x ∈ [√½ − 1, √2 − 1]: the full tail polynomial by Estrin's
/// scheme (6.8e-16 on a term ≤ 2e-4 of the sum).
template <class D>
HWY_INLINE V<D> Log1pPlain(D d, V<D> x) {
  return Log1pAtanh(d, x, [d](V<D> w) { return Estrin(d, w, poly::kAtanhTailDeg6); });
}

/// ln c = hi + lo for c > 0 finite (double lanes): e·ln2 + ln(1 + x), ln2 split so that e·ln2_hi
/// is exact. Relative error ~3e-20.
template <class D>
HWY_INLINE void LnDD(D d, V<D> c, V<D>& hi, V<D>& lo) {
  using T = hn::TFromD<D>;
  static_assert(sizeof(T) == 8, "LnDD works in double lanes");
  const V<D> ln2_hi = hn::Set(d, T(0.693147180369123816490));  // 32 significant bits
  const V<D> ln2_lo = hn::Set(d, T(1.90821492927058770002e-10));
  V<D> x, e, h, l;
  SplitExponent(d, c, x, e);
  Log1pDD(d, x, h, l);
  const V<D> s = hn::Mul(e, ln2_hi);
  const V<D> sum = hn::Add(s, h);
  const V<D> rest = hn::Add(hn::Add(hn::Sub(s, sum), h), hn::MulAdd(e, ln2_lo, l));  // |s| ≥ |h| or s = 0
  // Renormalized: l holds Log1pDD's z⁵P(w) (up to 2e-4 of the sum) and rest e·ln2_lo; with
  // |lo| ≤ ulp(hi), PowerExact's reduced argument stays within the polynomial's [−½, ½].
  hi = hn::Add(sum, rest);
  lo = hn::Add(hn::Sub(sum, hi), rest);
}

/// c clamped to ≤ 1, NaN kept (the scalar clamp_cos; c < 0 is masked by each kernel).
template <class D>
HWY_INLINE V<D> ClampAbove(D d, V<D> c) {
  const V<D> one = hn::Set(d, hn::TFromD<D>(1));
  return hn::IfThenElse(hn::Gt(c, one), one, c);
}

/// c clamped to [0, 1], NaN kept: the scalar clamp_cos.
template <class D>
HWY_INLINE V<D> ClampBoth(D d, V<D> c) {
  return hn::IfThenZeroElse(hn::Lt(c, hn::Zero(d)), ClampAbove(d, c));
}

/// r where c is a number, NaN where c is NaN.
template <class D>
HWY_INLINE V<D> KeepNaN(V<D> c, V<D> r) {
  return hn::IfThenElse(hn::IsNaN(c), c, r);
}

// ---------------------------------------------------------------------------------------------
// Lobes. Each kernel object holds its broadcast parameters; operator() maps cosines to F.

/// F = c^n, exact tier (double lanes): 2^(n log2 c) with n log2 c carried as hi + lo through
/// LnDD, then 2^k (1 + f·P₁₀(f)), f = (y_hi − k) + y_lo (2.04e-17 relative polynomial).
template <class D>
struct PowerExact {
  // Vector ops per vector, loads and stores not counted (the compute limit's numerator,
  // docs/simd.md): clamp 1, mask 1, LnDD 56 (its tail polynomial by Estrin), log2 as hi + lo 4,
  // y 3, reduction 3, Exp2Reduced 17 (Estrin), masks 3, KeepNaN 2.
  static constexpr int kOps = 90;
  D d;
  V<D> n;
  explicit PowerExact(D d_, double n_) : d(d_), n(hn::Set(d_, n_)) {}
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> cc = hn::Min(c, hn::Set(d, 1.0));  // NaN lanes: KeepNaN below
    const auto positive = hn::Gt(cc, hn::Zero(d));
    V<D> h, l;
    LnDD(d, cc, h, l);  // finite garbage where c ≤ 0, masked below
    const V<D> inv_ln2_hi = hn::Set(d, 1.4426950408889634074), inv_ln2_lo = hn::Set(d, 2.0355273740931033e-17);
    const V<D> lh = hn::Mul(h, inv_ln2_hi);  // log2 c = lh + ll
    const V<D> ll = hn::MulAdd(h, inv_ln2_lo, hn::MulAdd(l, inv_ln2_hi, ProductError(d, h, inv_ln2_hi, lh)));
    const V<D> yh = hn::Mul(n, lh);
    const V<D> yl = hn::MulAdd(n, ll, ProductError(d, n, lh, yh));
    const V<D> k = hn::Round(yh);
    const V<D> p = Exp2Reduced(d, hn::Add(hn::Sub(yh, k), yl), k, poly::kExp2m1Deg10);
    const auto live = hn::And(positive, hn::Ge(yh, hn::Set(d, Bits<double>::kMinExp2)));
    return KeepNaN<D>(c, hn::IfThenElseZero(live, p));
  }
};

/// F = c^n, fast tier: 2^(n log2 c) with Log2Fast and Exp2Fast.
template <class D>
struct PowerFast {
  // clamp 2, Log2Fast 23, y 1, masks 3, Exp2Fast 10, select 1, KeepNaN 2.
  static constexpr int kOps = 42;
  using T = hn::TFromD<D>;
  D d;
  V<D> n;
  PowerFast(D d_, double n_) : d(d_), n(hn::Set(d_, static_cast<T>(n_))) {}
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> cc = ClampAbove(d, c);
    const V<D> y = hn::Mul(n, Log2Fast(d, cc));
    const auto live = hn::And(hn::Gt(cc, hn::Zero(d)), hn::Ge(y, hn::Set(d, T(Bits<T>::kMinExp2))));
    return KeepNaN<D>(c, hn::IfThenElseZero(live, Exp2Fast(d, y)));
  }
};

/// F = c / (n(1 − c) + c) (Schlick 1994), both tiers; the fast one multiplies by a reciprocal.
template <class D, bool kFast>
struct Schlick {
  // clamp 4, 1 − c 1, FMA 1, divide 1 (fast float: reciprocal + Newton 3, multiply 1).
  static constexpr int kOps = kFast && sizeof(hn::TFromD<D>) == 4 ? 10 : 7;
  using T = hn::TFromD<D>;
  D d;
  V<D> n;
  Schlick(D d_, double n_) : d(d_), n(hn::Set(d_, static_cast<T>(n_))) {}
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> one = hn::Set(d, T(1));
    const V<D> cc = ClampBoth(d, c);
    const V<D> den = hn::MulAdd(n, hn::Sub(one, cc), cc);
    return kFast ? hn::Mul(cc, ReciprocalFast(d, den)) : hn::Div(cc, den);
  }
};

/// F = (s c / (n(1 − c) + s c))², both tiers.
template <class D, bool kFast>
struct SchlickModified {
  // clamp 4, s·c 1, 1 − c 1, FMA 1, divide 1 (fast float: 4), square 1.
  static constexpr int kOps = kFast && sizeof(hn::TFromD<D>) == 4 ? 12 : 9;
  using T = hn::TFromD<D>;
  D d;
  V<D> n, s;
  SchlickModified(D d_, double n_, double s_)
      : d(d_), n(hn::Set(d_, static_cast<T>(n_))), s(hn::Set(d_, static_cast<T>(s_))) {}
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> one = hn::Set(d, T(1));
    const V<D> cc = ClampBoth(d, c);
    const V<D> sc = hn::Mul(s, cc);
    const V<D> den = hn::MulAdd(n, hn::Sub(one, cc), sc);
    const V<D> q = kFast ? hn::Mul(sc, ReciprocalFast(d, den)) : hn::Div(sc, den);
    return hn::Mul(q, q);
  }
};

/// F = exp(−n θ²/2), θ = acos c, exact tier (double lanes): Highway's Acos and Exp, the argument
/// rounded as the scalar lobe rounds it.
template <class D>
struct GaussExact {
  // clamp 4, Highway's Acos 35 and Exp 35 (double), argument 3, mask 2.
  static constexpr int kOps = 79;
  D d;
  V<D> minus_n;
  GaussExact(D d_, double n_) : d(d_), minus_n(hn::Set(d_, -n_)) {}
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> cc = ClampBoth(d, c);
    const V<D> theta = hn::Acos(d, cc);
    const V<D> arg = hn::Mul(hn::Mul(hn::Mul(minus_n, theta), theta), hn::Set(d, 0.5));
    return hn::IfThenElseZero(hn::Gt(c, hn::Zero(d)), hn::Exp(d, arg));
  }
};

/// F = 2^(−n θ²/(2 ln 2)), fast tier: θ² = x·P₅(x) with x = 1 − c (acos(1 − x)²/x is smooth
/// on [0, 1]), then Exp2Fast.
template <class D>
struct GaussFast {
  // clamp 2, 1 − c 1, polynomial 5, argument 2, masks 3, Exp2Fast 10, select 1.
  static constexpr int kOps = 24;
  using T = hn::TFromD<D>;
  D d;
  V<D> k;  ///< −n/(2 ln 2)
  GaussFast(D d_, double n_) : d(d_), k(hn::Set(d_, static_cast<T>(-n_ / (2 * 0.693147180559945309417)))) {}
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> x = hn::Sub(hn::Set(d, T(1)), ClampAbove(d, c));
    const V<D> y = hn::Mul(k, hn::Mul(x, Horner(d, x, poly::kAcos2Deg5)));
    const auto live = hn::And(hn::Gt(c, hn::Zero(d)), hn::Ge(y, hn::Set(d, T(Bits<T>::kMinExp2))));
    return hn::IfThenElseZero(live, Exp2Fast(d, y));
  }
};

/// log2(1 + t) on t ∈ [0, 3] as A + x·P(x) with x ∈ [√½ − 1, √2 − 1] (docs/math.md §3 t-space):
///   t < √2 − 1:        x = t,            F = 1 − ½ log2(1 + x)
///   t < 2√2 − 1:       x = (t − 1)/2,    F = ½ − ½ log2(1 + x)
///   otherwise:         x = (t − 3)/4,    F = −½ log2(1 + x)
/// The last case has no cancellation as F → 0 at the cut-off t = 3, given x (= −(3 − t)/4)
/// to a few ulp: 3 − t comes from one FMA.
template <class D>
struct LogCases {
  V<D> x, a;
};

template <class D>
HWY_INLINE LogCases<D> log_cases(D d, V<D> t, V<D> three_minus_t) {
  using T = hn::TFromD<D>;
  const auto first = hn::Lt(t, hn::Set(d, T(0.41421356237309504880)));
  const auto last = hn::Ge(t, hn::Set(d, T(1.82842712474619009760)));
  const V<D> half = hn::Set(d, T(0.5)), quarter = hn::Set(d, T(0.25));
  const V<D> middle_x = hn::MulSub(t, half, half);
  const V<D> x = hn::IfThenElse(first, t, hn::IfThenElse(last, hn::Mul(three_minus_t, hn::Neg(quarter)), middle_x));
  const V<D> a = hn::IfThenElse(first, hn::Set(d, T(1)), hn::IfThenZeroElse(last, half));
  return {x, a};
}

/// log2 c for c > 0, not subnormal, to ~1e-13 relative (double lanes holding float inputs).
template <class D>
HWY_INLINE V<D> Log2Short(D d, V<D> c) {
  V<D> x, e;
  SplitExponent<false>(d, c, x, e);
  return hn::MulAdd(Log1pShort(d, x), hn::Set(d, 1.4426950408889634074), e);
}

#if HWY_TARGET != HWY_SCALAR
/// F = 2^y for float arrays with y = Log2F(c) computed in double lanes: y split into k = round(y)
/// and f = y − k, and 2^k (1 + f·P₅(f)) in float lanes (P₅: 1.22e-8), so that the exponential
/// runs at the float vector width. F = 0 where c ≤ 0 or k < −125 (F < 2⁻¹²⁵·⁵); NaN kept.
template <class DF, class Log2F>
struct Exp2InFloatLanes {
  using DD = hn::Rebind<double, hn::Half<DF>>;
  DF df;
  Log2F log2_f;  ///< V<DD> → V<DD>: log₂ F of c in [0, 1] (promoted), any finite value elsewhere
  HWY_INLINE void Reduce(hn::VFromD<hn::Half<DF>> c, V<DD>& f, V<DD>& k) const {
    const DD dd;
    const V<DD> y = hn::Max(log2_f(hn::PromoteTo(dd, c)), hn::Set(dd, -200.0));
    k = hn::Round(y);
    f = hn::Sub(y, k);
  }
  HWY_INLINE V<DF> operator()(V<DF> c) const {
    const hn::Half<DF> dh;
    const hn::RebindToSigned<DF> di;
    const hn::Half<decltype(di)> dih;
    const V<DF> cc = ClampAbove(df, c);
    V<DD> f0, k0, f1, k1;
    Reduce(hn::LowerHalf(dh, cc), f0, k0);
    Reduce(hn::UpperHalf(dh, cc), f1, k1);
    const V<DF> f = hn::Combine(df, hn::DemoteTo(dh, f1), hn::DemoteTo(dh, f0));
    const auto k = hn::Combine(di, hn::DemoteTo(dih, k1), hn::DemoteTo(dih, k0));
    const V<DF> p = hn::MulAdd(f, Horner(df, f, poly::kExp2m1Deg5), hn::Set(df, 1.0f));
    const V<DF> r = hn::BitCast(df, hn::Add(hn::BitCast(di, p), hn::ShiftLeft<23>(k)));
    const auto live = hn::And(hn::Gt(cc, hn::Zero(df)), hn::RebindMask(df, hn::Gt(k, hn::Set(di, -126))));
    return KeepNaN<DF>(c, hn::IfThenElseZero(live, r));
  }
};

/// log₂ c^n = n log₂ c, ~1e-13 relative (Log2Short).
template <class DD>
struct Log2Power {
  V<DD> n;
  HWY_INLINE V<DD> operator()(V<DD> c) const { return hn::Mul(n, Log2Short(DD(), c)); }
};

/// log₂ of the Gauss lobe, −n θ²/(2 ln 2) with θ² = x·P₁₁(x), x = 1 − c (2.4e-11 relative).
template <class DD>
struct Log2Gauss {
  V<DD> k;  ///< −n/(2 ln 2)
  HWY_INLINE V<DD> operator()(V<DD> c) const {
    const DD dd;
    const V<DD> x = hn::Sub(hn::Set(dd, 1.0), c);
    return hn::Mul(k, hn::Mul(x, Estrin(dd, x, poly::kAcos2Deg11)));
  }
};

/// F = c^n, exact tier of float arrays.
template <class DF>
struct PowerExactFloat : Exp2InFloatLanes<DF, Log2Power<hn::Rebind<double, hn::Half<DF>>>> {
  // Per float vector: clamp 2, upper half 1, per half (promote 1, Log2Short 18, y 1, split 3) 46,
  // demote 4, combine 2, exponential 8, masks 4, KeepNaN 2.
  static constexpr int kOps = 69;
  PowerExactFloat(DF df, double n) : PowerExactFloat::Exp2InFloatLanes{df, {hn::Set(typename PowerExactFloat::DD(), n)}} {}
};

/// F = exp(−n θ²/2), exact tier of float arrays. (The scalar lobe gives 0 for NaN: c > 0 is false.)
template <class DF>
struct GaussExactFloat : Exp2InFloatLanes<DF, Log2Gauss<hn::Rebind<double, hn::Half<DF>>>> {
  // Per float vector: clamp 2, upper half 1, per half (promote 1, 1 − c 1, polynomial 14 (Estrin),
  // y 2, split 3) 42, demote 4, combine 2, exponential 8, masks 4, KeepNaN 2, NaN to 0 2.
  static constexpr int kOps = 67;
  GaussExactFloat(DF df, double n)
      : GaussExactFloat::Exp2InFloatLanes{df, {hn::Set(typename GaussExactFloat::DD(), -n / (2 * 0.693147180559945309417))}} {}
  HWY_INLINE V<DF> operator()(V<DF> c) const {
    return hn::IfThenElseZero(hn::Gt(c, hn::Zero(this->df)), GaussExactFloat::Exp2InFloatLanes::operator()(c));
  }
};

#endif  // HWY_TARGET != HWY_SCALAR

/// PowerExactFloat for the one-lane SCALAR target: all in double lanes.
template <class D>
struct PowerExactFloatScalar {
  static constexpr int kOps = 43;  // as PowerExactFloat, per lane, in double
  D d;
  V<D> n;
  PowerExactFloatScalar(D d_, double n_) : d(d_), n(hn::Set(d_, n_)) {}
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> cc = ClampAbove(d, c);
    const V<D> y = hn::Mul(n, Log2Short(d, cc));
    const auto live = hn::And(hn::Gt(cc, hn::Zero(d)), hn::Ge(y, hn::Set(d, -125.5)));
    return KeepNaN<D>(c, hn::IfThenElseZero(live, Exp2Poly(d, y, poly::kExp2m1Deg10)));
  }
};

/// For n ≥ 6 the support of the log lobe, c > c₀ = 2^(−3/n) ≥ √½, lies where c = 1 + x with
/// x ∈ [√½ − 1, 0] needs no exponent: the kernels skip SplitExponent (kNearOne) and zero c ≤ √½.
inline constexpr double kNearOneMinN = 6;

/// F_log, exact tier, in double lanes: t = −n log2 c to ~2.5 ulp, 3 − t from one FMA, then the
/// three cases of log_cases, so that F keeps its relative accuracy down to |F| ~ 1e-15 near the
/// cut-off (the scalar lobe's own error there is 4e-16 absolute). kFloat: float arrays (no
/// subnormal doubles; the shorter polynomial for the outer logarithm, ~1e-13 relative to F).
template <class D, bool kFloat, bool kNearOne>
struct LogExact {
  // clamp 1, log2 c (kNearOne: 17; else split 12 (7 for kFloat) + 16), 3 − t 1, t 1, cases 8,
  // outer log (15; kFloat 10), F 1, masks 4, KeepNaN 2 (kFloat: promote and demote counted by the caller).
  static constexpr int kOps = (kNearOne ? 50 : 61) - (kFloat ? 5 : 0) - (kFloat && !kNearOne ? 5 : 0);
  D d;
  V<D> n, minus_n;
  LogExact(D d_, double n_) : d(d_), n(hn::Set(d_, n_)), minus_n(hn::Set(d_, -n_)) {}
  /// The outer logarithm: F's relative error follows its own, so float arrays take the short one.
  HWY_INLINE V<D> OuterLn1p(V<D> x) const { return kFloat ? Log1pShort(d, x) : Log1pPlain(d, x); }
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> cc = hn::Min(c, hn::Set(d, 1.0));  // NaN lanes: KeepNaN below
    const V<D> inv_ln2 = hn::Set(d, 1.4426950408889634074);
    V<D> l;  // log2 c
    if constexpr (kNearOne) {
      l = hn::Mul(Log1pPlain(d, hn::Sub(cc, hn::Set(d, 1.0))), inv_ln2);
    } else {
      V<D> x, e;
      SplitExponent<!kFloat>(d, cc, x, e);
      l = hn::MulAdd(Log1pPlain(d, x), inv_ln2, e);
    }
    const V<D> three_minus_t = hn::MulAdd(n, l, hn::Set(d, 3.0));
    const LogCases<D> k = log_cases(d, hn::Mul(minus_n, l), three_minus_t);
    const V<D> f = hn::NegMulAdd(OuterLn1p(k.x), hn::Set(d, 0.72134752044448170368), k.a);  // a − ln(1 + x)/(2 ln 2)
    const V<D> lowest = hn::Set(d, kNearOne ? 0.70710678118654752440 : 0.0);
    const auto live = hn::And(hn::Gt(cc, lowest), hn::Gt(three_minus_t, hn::Zero(d)));
    return KeepNaN<D>(c, hn::IfThenElseZero(live, f));
  }
};

/// F_log, fast tier ("a log of a log"): one Log2Fast of c to ~1 ulp, then log2(1 + t) on the
/// fixed range t ∈ [0, 3] with the degree-5 polynomial (8.3e-6), which is enough for 1e-4
/// relative wherever F ≥ 1e-3.
template <class D, bool kNearOne>
struct LogFast {
  // clamp 1, log2 c (kNearOne: 11, else Log2Fast 23), t 1, 3 − t 1, cases 8, polynomial 5,
  // F 2, masks 4, KeepNaN 2.
  static constexpr int kOps = kNearOne ? 36 : 48;
  using T = hn::TFromD<D>;
  D d;
  V<D> n, minus_n;
  LogFast(D d_, double n_) : d(d_), n(hn::Set(d_, static_cast<T>(n_))), minus_n(hn::Neg(n)) {}
  HWY_INLINE V<D> operator()(V<D> c) const {
    const V<D> cc = hn::Min(c, hn::Set(d, T(1)));  // NaN lanes: KeepNaN below
    const V<D> l = kNearOne ? Log2FastReduced(d, hn::Sub(cc, hn::Set(d, T(1)))) : Log2Fast(d, cc);
    const V<D> t = hn::Mul(minus_n, l);
    const V<D> three_minus_t = hn::MulAdd(n, l, hn::Set(d, T(3)));
    const LogCases<D> k = log_cases(d, t, three_minus_t);
    const V<D> p = Horner(d, k.x, poly::kLog2p1Deg5);
    const V<D> f = hn::NegMulAdd(hn::Mul(k.x, hn::Set(d, T(0.5))), p, k.a);
    const V<D> lowest = hn::Set(d, T(kNearOne ? 0.70710678118654752440 : 0.0));
    const auto live = hn::And(hn::Gt(cc, lowest), hn::Gt(three_minus_t, hn::Zero(d)));
    return KeepNaN<D>(c, hn::IfThenElseZero(live, f));
  }
};

// ---------------------------------------------------------------------------------------------
// Loops over arrays

/// out[i] = kernel(c[i]) for i < count; the tail runs through one padded vector. kUnroll
/// independent vectors per iteration (2 or 4) let the core overlap the kernels' dependency
/// chains; the long exact kernels take 2, so that their constants stay in registers.
template <int kUnroll = 4, class D, class Kernel>
HWY_INLINE void Apply(D d, const Kernel& kernel, const hn::TFromD<D>* HWY_RESTRICT c, std::size_t count,
                      hn::TFromD<D>* HWY_RESTRICT out) {
  using T = hn::TFromD<D>;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + kUnroll * lanes <= count; i += kUnroll * lanes) {
    const V<D> r0 = kernel(hn::LoadU(d, c + i)), r1 = kernel(hn::LoadU(d, c + i + lanes));
    if constexpr (kUnroll == 4) {
      const V<D> r2 = kernel(hn::LoadU(d, c + i + 2 * lanes)), r3 = kernel(hn::LoadU(d, c + i + 3 * lanes));
      hn::StoreU(r2, d, out + i + 2 * lanes);
      hn::StoreU(r3, d, out + i + 3 * lanes);
    }
    hn::StoreU(r0, d, out + i);
    hn::StoreU(r1, d, out + i + lanes);
  }
  for (; i + lanes <= count; i += lanes) hn::StoreU(kernel(hn::LoadU(d, c + i)), d, out + i);
  if (i == count) return;
  HWY_ALIGN T buffer[hn::MaxLanes(d)];
  for (std::size_t j = 0; j < lanes; ++j) buffer[j] = i + j < count ? c[i + j] : T(1);
  hn::Store(kernel(hn::Load(d, buffer)), d, buffer);
  std::memcpy(out + i, buffer, (count - i) * sizeof(T));
}

/// As Apply, for float arrays through a kernel in double lanes (the exact tier's float path):
/// each half-width float vector is promoted, evaluated and rounded back once.
template <class DD, class Kernel>
HWY_INLINE void ApplyPromoted(DD dd, const Kernel& kernel, const float* HWY_RESTRICT c, std::size_t count,
                              float* HWY_RESTRICT out) {
  const hn::Rebind<float, DD> df;
  const std::size_t lanes = hn::Lanes(dd);
  auto step = [&](auto v) { return hn::DemoteTo(df, kernel(hn::PromoteTo(dd, v))); };
  std::size_t i = 0;
  for (; i + 2 * lanes <= count; i += 2 * lanes) {
    const auto r0 = step(hn::LoadU(df, c + i)), r1 = step(hn::LoadU(df, c + i + lanes));
    hn::StoreU(r0, df, out + i);
    hn::StoreU(r1, df, out + i + lanes);
  }
  for (; i + lanes <= count; i += lanes) hn::StoreU(step(hn::LoadU(df, c + i)), df, out + i);
  if (i == count) return;
  HWY_ALIGN float buffer[hn::MaxLanes(df)];
  for (std::size_t j = 0; j < lanes; ++j) buffer[j] = i + j < count ? c[i + j] : 1.0f;
  hn::Store(step(hn::Load(df, buffer)), df, buffer);
  std::memcpy(out + i, buffer, (count - i) * sizeof(float));
}

}  // namespace specula::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // SPECULA_SIMD_KERNELS_INL_H_
