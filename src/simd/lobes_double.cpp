// Batch lobe evaluation for double arrays, compiled for every Highway target and picked at run
// time (HWY_DYNAMIC_DISPATCH); lobes.cpp holds float arrays and the API.
#include <cstddef>

#include "src/simd/lobes_double.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/simd/lobes_double.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"
#include "src/simd/lobe_kernel-inl.h"

HWY_BEFORE_NAMESPACE();
namespace specula::simd::HWY_NAMESPACE {

void EvalLobeF64(const LobeSpec& lobe, Tier tier, const double* c, std::size_t count, double* out) {
  RunLobe(lobe, tier, c, count, out);
}

double OpsPerValueF64(const LobeSpec& lobe, Tier tier) { return OpsPerValue<double>(lobe, tier); }

}  // namespace specula::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace specula::simd {

HWY_EXPORT(EvalLobeF64);
HWY_EXPORT(OpsPerValueF64);

void eval_lobe_double(const LobeSpec& lobe, Tier tier, const double* c, std::size_t count, double* out) noexcept {
  HWY_DYNAMIC_DISPATCH(EvalLobeF64)(lobe, tier, c, count, out);
}

double ops_per_value_double(const LobeSpec& lobe, Tier tier) { return HWY_DYNAMIC_DISPATCH(OpsPerValueF64)(lobe, tier); }

}  // namespace specula::simd
#endif
