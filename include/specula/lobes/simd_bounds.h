#pragma once
// The vocabulary of the SIMD tiers, below the families that state their bounds in it
// (families/<family>.h, `bounds`) and the dispatch that meets them (simd/lobes.h, where the bounds'
// meaning is documented): the tiers, the kernel families and an error bound's form.
#include <concepts>
#include <cstddef>

#include "specula/exceptions.h"

namespace specula::simd {

enum class Tier { exact, fast };

/// How many tiers there are (`fast` is the last; names_complete below fails on one added after it).
inline constexpr std::size_t kTierCount = static_cast<std::size_t>(Tier::fast) + 1;

/// "exact" or "fast": the tiers' names ("" outside the enum).
constexpr const char* to_string(Tier tier) noexcept {
  switch (tier) {
    case Tier::exact: return "exact";
    case Tier::fast: return "fast";
  }
  return "";
}
static_assert(names_complete<Tier, kTierCount>([](Tier t) { return to_string(t); }));

/// The lobe families, in lobes::Lobe's order.
enum class Family { power, schlick, schlick_modified, gauss, log, formula };

/// How many families there are (`formula` is the last): a table indexed by Family has this many.
inline constexpr std::size_t kFamilyCount = static_cast<std::size_t>(Family::formula) + 1;

/// A tier's error bound against the scalar double lobe (what it means: the top of simd/lobes.h).
struct ErrorBound {
  double rel = 0;
  double rel_per_ln = 0;
  double abs = 0;
  double floor = 0;
  double abs_below = 0;

  /// The largest |F̃ − F| allowed where the reference is F.
  constexpr double allowed(double f, double ln_f) const noexcept {
    return f >= floor ? (rel + rel_per_ln * (ln_f < 0 ? -ln_f : ln_f)) * f + abs : abs_below;
  }
};

/// The formula rows of simd/lobes.h's table (simd/formula.h's path): measured over the user-written
/// copies of the built-in lobes, the largest with a little room.
template <std::floating_point T>
constexpr ErrorBound formula_error_bound(Tier tier) noexcept {
  constexpr double eps = 0x1p-52;
  if (sizeof(T) == 8) return {16 * eps, 4 * eps, 4 * eps, 0x1p-1022, 0x1p-1022};
  if (tier == Tier::exact) return {0x1p-24 + 16 * eps, 4 * eps, 4 * eps, 0x1p-126, 0x1p-126};
  return {1e-4, 0, 0, 1e-3, 1e-6};
}

}  // namespace specula::simd
