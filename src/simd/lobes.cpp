// Batch lobe evaluation: one function per lane type, compiled for every Highway target and
// picked at run time (HWY_DYNAMIC_DISPATCH); the kernel is chosen once per batch
// (lobe_kernel-inl.h). This file holds float arrays and the API; lobes_double.cpp double
// arrays (two files so that two cores compile them).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <variant>

#include "specula/simd/formula.h"
#include "specula/simd/lobes.h"
#include "src/simd/lobes_double.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/simd/lobes.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"
#include "src/simd/lobe_kernel-inl.h"

HWY_BEFORE_NAMESPACE();
namespace specula::simd::HWY_NAMESPACE {

void EvalLobeF32(const LobeSpec& lobe, Tier tier, const float* c, std::size_t count, float* out) {
  RunLobe(lobe, tier, c, count, out);
}

double OpsPerValueF32(const LobeSpec& lobe, Tier tier) { return OpsPerValue<float>(lobe, tier); }

}  // namespace specula::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace specula::simd {

HWY_EXPORT(EvalLobeF32);
HWY_EXPORT(OpsPerValueF32);

LobeSpec spec_of(const lobes::Lobe& lobe) noexcept {
  return std::visit([](const auto& l) { return spec_of(l); }, lobe);
}

void eval_batch(const LobeSpec& lobe, Tier tier, std::span<const float> c, std::span<float> out) noexcept {
  if (lobe.family == Family::formula) return eval_formula(*lobe.formula, tier, c, out);
  HWY_DYNAMIC_DISPATCH(EvalLobeF32)(lobe, tier, c.data(), std::min(c.size(), out.size()), out.data());
}

void eval_batch(const LobeSpec& lobe, Tier tier, std::span<const double> c, std::span<double> out) noexcept {
  if (lobe.family == Family::formula) return eval_formula(*lobe.formula, tier, c, out);
  eval_lobe_double(lobe, tier, c.data(), std::min(c.size(), out.size()), out.data());
}

double ops_per_value(const LobeSpec& lobe, Tier tier, bool single_precision) {
  if (lobe.family == Family::formula) return double(lobe.formula->definition().any().node_count());
  return single_precision ? HWY_DYNAMIC_DISPATCH(OpsPerValueF32)(lobe, tier) : ops_per_value_double(lobe, tier);
}

}  // namespace specula::simd
#endif
