// The SIMD bounds the family definitions state (include/specula/families/), and whether the
// dispatch has kernels for them.
#include "specula/families/families.h"
#include "specula/simd/lobes.h"

namespace specula::simd {

template <std::floating_point T>
ErrorBound error_bound(Family family, Tier tier) noexcept {
  if (family == Family::formula) return formula_error_bound<T>(tier);
  return families::lobe_family(family).bounds.of(tier, sizeof(T) == 4);
}

template ErrorBound error_bound<float>(Family, Tier) noexcept;
template ErrorBound error_bound<double>(Family, Tier) noexcept;

bool has_kernel(Family family, Tier tier) {
  if (family == Family::formula) return false;
  const LobeSpec spec{family};
  return ops_per_value(spec, tier, true) > 0 && ops_per_value(spec, tier, false) > 0;
}

}  // namespace specula::simd
