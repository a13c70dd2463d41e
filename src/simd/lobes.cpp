// Batch lobe evaluation: one function per lane type, compiled for every Highway target and
// picked at run time (HWY_DYNAMIC_DISPATCH). The choice of kernel (family, tier, the log lobe's
// n ≥ 6 shortcut) happens once per batch, in WithKernel, which also serves the kernels' operation
// counts to the benchmark.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <variant>

#include "specula/simd/formula.h"
#include "specula/simd/lobes.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/simd/lobes.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"
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

void EvalLobeF32(const LobeSpec& lobe, Tier tier, const float* c, std::size_t count, float* out) {
  RunLobe(lobe, tier, c, count, out);
}

void EvalLobeF64(const LobeSpec& lobe, Tier tier, const double* c, std::size_t count, double* out) {
  RunLobe(lobe, tier, c, count, out);
}

double OpsPerValueF32(const LobeSpec& lobe, Tier tier) { return OpsPerValue<float>(lobe, tier); }
double OpsPerValueF64(const LobeSpec& lobe, Tier tier) { return OpsPerValue<double>(lobe, tier); }

}  // namespace specula::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace specula::simd {

HWY_EXPORT(EvalLobeF32);
HWY_EXPORT(EvalLobeF64);
HWY_EXPORT(OpsPerValueF32);
HWY_EXPORT(OpsPerValueF64);

LobeSpec spec_of(const lobes::Lobe& lobe) noexcept {
  return std::visit([](const auto& l) { return spec_of(l); }, lobe);
}

void eval_batch(const LobeSpec& lobe, Tier tier, std::span<const float> c, std::span<float> out) noexcept {
  if (lobe.family == Family::formula) return eval_formula(*lobe.formula, tier, c, out);
  HWY_DYNAMIC_DISPATCH(EvalLobeF32)(lobe, tier, c.data(), std::min(c.size(), out.size()), out.data());
}

void eval_batch(const LobeSpec& lobe, Tier tier, std::span<const double> c, std::span<double> out) noexcept {
  if (lobe.family == Family::formula) return eval_formula(*lobe.formula, tier, c, out);
  HWY_DYNAMIC_DISPATCH(EvalLobeF64)(lobe, tier, c.data(), std::min(c.size(), out.size()), out.data());
}

double ops_per_value(const LobeSpec& lobe, Tier tier, bool single_precision) {
  if (lobe.family == Family::formula) return double(lobe.formula->definition().any().node_count());
  return single_precision ? HWY_DYNAMIC_DISPATCH(OpsPerValueF32)(lobe, tier)
                          : HWY_DYNAMIC_DISPATCH(OpsPerValueF64)(lobe, tier);
}

}  // namespace specula::simd
#endif
