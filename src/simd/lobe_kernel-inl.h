// The choice of a lobe's SIMD kernel for arrays of T, once per Highway target: WithKernel picks
// the kernel (family, tier, the log lobe's n ≥ 6 shortcut) once per batch, RunLobe applies it,
// OpsPerValue counts its operations for the benchmark. Included by lobes.cpp (float arrays) and
// lobes_double.cpp (double arrays), each compiled for every target, side by side.

// Per-target include guard (Highway's idiom: toggled once per target).
#if defined(SPECULA_SIMD_LOBE_KERNEL_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef SPECULA_SIMD_LOBE_KERNEL_INL_H_
#undef SPECULA_SIMD_LOBE_KERNEL_INL_H_
#else
#define SPECULA_SIMD_LOBE_KERNEL_INL_H_
#endif

#include <cmath>
#include <cstddef>
#include <type_traits>

#include "hwy/highway.h"
#include "specula/simd/lobes.h"
#include "src/simd/kernels-inl.h"

HWY_BEFORE_NAMESPACE();
namespace specula::simd::HWY_NAMESPACE {

/// How a kernel meets arrays of T: in its own lanes, or (float arrays, exact tier) promoted to
/// double lanes and rounded back.
enum class Lanes { native, promoted };

/// The kernel of a family that has none of its own: NaN, and no operations counted
/// (has_kernel tells it apart by that).
template <class D>
struct NoKernel {
  static constexpr int kOps = 0;
  D d;
  HWY_INLINE V<D> operator()(V<D>) const { return hn::Set(d, hn::TFromD<D>(NAN)); }
};

/// visit(d, kernel, lanes) with the kernel that evaluates `lobe` at `tier` for arrays of T.
template <class T, class Visit>
auto WithKernel(const LobeSpec& lobe, Tier tier, const Visit& visit) {
  using D = hn::ScalableTag<T>;
  using DD = hn::ScalableTag<double>;
  const D d;
  const DD dd;
  constexpr bool is_float = sizeof(T) == 4;
  constexpr Lanes exact_lanes = is_float ? Lanes::promoted : Lanes::native;
  const bool fast = tier == Tier::fast;
  const bool near_one = lobe.n >= kNearOneMinN;
  switch (lobe.family) {
    case Family::power:
      if (fast) return visit(d, PowerFast<D>(d, lobe.n), Lanes::native);
      if constexpr (!is_float) {
        return visit(dd, PowerExact<DD>(dd, lobe.n), Lanes::native);
      } else {
#if HWY_TARGET == HWY_SCALAR  // one lane: no halves to split a float vector into
        return visit(dd, PowerExactFloatScalar<DD>(dd, lobe.n), Lanes::promoted);
#else
        return visit(d, PowerExactFloat<D>(d, lobe.n), Lanes::native);
#endif
      }
    case Family::schlick:
      return fast ? visit(d, Schlick<D, true>(d, lobe.n), Lanes::native)
                  : visit(d, Schlick<D, false>(d, lobe.n), Lanes::native);
    case Family::schlick_modified:
      return fast ? visit(d, SchlickModified<D, true>(d, lobe.n, lobe.s), Lanes::native)
                  : visit(d, SchlickModified<D, false>(d, lobe.n, lobe.s), Lanes::native);
    case Family::gauss:
      if (fast) return visit(d, GaussFast<D>(d, lobe.n), Lanes::native);
#if HWY_TARGET != HWY_SCALAR
      if constexpr (is_float) return visit(d, GaussExactFloat<D>(d, lobe.n), Lanes::native);
#endif
      return visit(dd, GaussExact<DD>(dd, lobe.n), exact_lanes);
    case Family::log:
      if (fast) return near_one ? visit(d, LogFast<D, true>(d, lobe.n), Lanes::native)
                                : visit(d, LogFast<D, false>(d, lobe.n), Lanes::native);
      return near_one ? visit(dd, LogExact<DD, is_float, true>(dd, lobe.n), exact_lanes)
                      : visit(dd, LogExact<DD, is_float, false>(dd, lobe.n), exact_lanes);
    case Family::formula: break;  // never dispatched: eval_batch sends formulas to simd/formula.h
  }
  return visit(d, NoKernel<D>{d}, Lanes::native);
}

template <class T>
void RunLobe(const LobeSpec& lobe, Tier tier, const T* c, std::size_t count, T* out) {
  WithKernel<T>(lobe, tier, [&](auto d, const auto& kernel, Lanes lanes) {
    using K = std::decay_t<decltype(kernel)>;
    constexpr int kUnroll = K::kOps > 60 ? 2 : 4;  // long kernels: keep their constants in registers
    if constexpr (std::is_same_v<hn::TFromD<decltype(d)>, T>) {
      Apply<kUnroll>(d, kernel, c, count, out);
    } else if constexpr (sizeof(T) == 4) {
      if (lanes == Lanes::promoted) ApplyPromoted(d, kernel, c, count, out);
    }
  });
}

/// The kernel's vector operations per evaluated value on this target (its kOps over its lanes).
template <class T>
double OpsPerValue(const LobeSpec& lobe, Tier tier) {
  return WithKernel<T>(lobe, tier, [](auto d, const auto& kernel, Lanes lanes) {
    (void)kernel;
    const int ops = std::decay_t<decltype(kernel)>::kOps + (lanes == Lanes::promoted ? 2 : 0);
    return double(ops) / double(hn::Lanes(d));
  });
}

}  // namespace specula::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // SPECULA_SIMD_LOBE_KERNEL_INL_H_
