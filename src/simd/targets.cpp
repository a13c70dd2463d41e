// Highway target information and the ScopedTarget used by tests.
#include <chrono>
#include <cstddef>

#include "specula/simd/targets.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "src/simd/targets.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"

HWY_BEFORE_NAMESPACE();
namespace specula::simd::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

TargetInfo CurrentTarget() {
  return {hwy::TargetName(HWY_TARGET), hn::Lanes(hn::ScalableTag<float>()), hn::Lanes(hn::ScalableTag<double>())};
}

double MeasureFmaPerSecond(double seconds) {
  const hn::ScalableTag<float> d;
  using V = hn::VFromD<decltype(d)>;
  V a[12];
  for (int i = 0; i < 12; ++i) a[i] = hn::Set(d, 1.0f + 0.01f * float(i));
  const V m = hn::Set(d, 0.999999f), b = hn::Set(d, 1e-7f);
  constexpr long kBlock = 1 << 16;
  long blocks = 0;
  const auto start = std::chrono::steady_clock::now();
  double elapsed = 0;
  do {
    for (long i = 0; i < kBlock; ++i)
      for (V& v : a) v = hn::MulAdd(v, m, b);
    ++blocks;
    elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  } while (elapsed < seconds);
  V sum = a[0];
  for (int i = 1; i < 12; ++i) sum = hn::Add(sum, a[i]);
  volatile float sink = hn::GetLane(sum);  // keeps the accumulators alive
  (void)sink;
  return double(blocks) * kBlock * 12 / elapsed;
}

void StreamCopy(const float* HWY_RESTRICT in, float* HWY_RESTRICT out, std::size_t count) {
  const hn::ScalableTag<float> d;
  const std::size_t lanes = hn::Lanes(d);
  std::size_t i = 0;
  for (; i + 4 * lanes <= count; i += 4 * lanes) {  // unrolled as the lobe loops are
    const auto a = hn::LoadU(d, in + i), b = hn::LoadU(d, in + i + lanes);
    const auto c = hn::LoadU(d, in + i + 2 * lanes), e = hn::LoadU(d, in + i + 3 * lanes);
    hn::StoreU(a, d, out + i);
    hn::StoreU(b, d, out + i + lanes);
    hn::StoreU(c, d, out + i + 2 * lanes);
    hn::StoreU(e, d, out + i + 3 * lanes);
  }
  for (; i + lanes <= count; i += lanes) hn::StoreU(hn::LoadU(d, in + i), d, out + i);
  for (; i < count; ++i) out[i] = in[i];
}

float StreamSum(const float* HWY_RESTRICT in, std::size_t count) {
  const hn::ScalableTag<float> d;
  const std::size_t lanes = hn::Lanes(d);
  auto s0 = hn::Zero(d), s1 = hn::Zero(d), s2 = hn::Zero(d), s3 = hn::Zero(d);
  std::size_t i = 0;
  for (; i + 4 * lanes <= count; i += 4 * lanes) {  // four chains: the adds' latency is hidden
    s0 = hn::Add(s0, hn::LoadU(d, in + i));
    s1 = hn::Add(s1, hn::LoadU(d, in + i + lanes));
    s2 = hn::Add(s2, hn::LoadU(d, in + i + 2 * lanes));
    s3 = hn::Add(s3, hn::LoadU(d, in + i + 3 * lanes));
  }
  float sum = hn::GetLane(hn::SumOfLanes(d, hn::Add(hn::Add(s0, s1), hn::Add(s2, s3))));
  for (; i < count; ++i) sum += in[i];
  return sum;
}

}  // namespace specula::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace specula::simd {

HWY_EXPORT(CurrentTarget);
HWY_EXPORT(MeasureFmaPerSecond);
HWY_EXPORT(StreamCopy);
HWY_EXPORT(StreamSum);

TargetInfo current_target() { return HWY_DYNAMIC_DISPATCH(CurrentTarget)(); }

double measure_fma_per_second(double seconds) { return HWY_DYNAMIC_DISPATCH(MeasureFmaPerSecond)(seconds); }

void stream_copy(const float* in, float* out, std::size_t count) { HWY_DYNAMIC_DISPATCH(StreamCopy)(in, out, count); }

float stream_sum(const float* in, std::size_t count) { return HWY_DYNAMIC_DISPATCH(StreamSum)(in, count); }

std::vector<std::int64_t> runnable_targets() {
  std::vector<std::int64_t> targets;
  for (std::int64_t t : hwy::SupportedAndGeneratedTargets()) targets.push_back(t);
  return targets;
}

std::string target_name(std::int64_t target) { return hwy::TargetName(target); }

ScopedTarget::ScopedTarget(std::int64_t target) { hwy::SetSupportedTargetsForTest(target); }

ScopedTarget::~ScopedTarget() { hwy::SetSupportedTargetsForTest(0); }

}  // namespace specula::simd
#endif
