// What the family definitions (include/specula/families/) answer at run time: the SIMD bounds
// they state, and whether the SIMD dispatch has kernels for them.
#include "specula/families/families.h"

namespace specula {

template <std::floating_point T>
simd::ErrorBound simd::error_bound(Family family, Tier tier) noexcept {
  if (family == Family::formula) return formula_error_bound<T>(tier);
  return families::lobe_family(family).bounds.of(tier, sizeof(T) == 4);
}

template simd::ErrorBound simd::error_bound<float>(simd::Family, simd::Tier) noexcept;
template simd::ErrorBound simd::error_bound<double>(simd::Family, simd::Tier) noexcept;

bool families::has_kernel(simd::Family family, simd::Tier tier) {
  if (family == simd::Family::formula) return false;
  const simd::LobeSpec spec{family};
  return simd::ops_per_value(spec, tier, true) > 0 && simd::ops_per_value(spec, tier, false) > 0;
}

}  // namespace specula
