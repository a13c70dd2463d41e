#pragma once
// Every lobe family, and `Lobe`: any of them chosen at run time (the registry's view). Each
// built-in family's definition, its name included, is include/specula/families/<family>.h.
#include <span>
#include <variant>

#include "specula/lobes/formula.h"
#include "specula/lobes/gauss.h"
#include "specula/lobes/log.h"
#include "specula/lobes/power.h"
#include "specula/lobes/schlick.h"
#include "specula/lobes/simd_bounds.h"

namespace specula::lobes {

using Lobe = std::variant<Power<double>, Schlick<double>, SchlickModified<double>, Gauss<double>,
                          Log<double>, Formula>;
// simd::Family names Lobe's alternatives in this order, one enumerator each.
static_assert(std::variant_size_v<Lobe> == simd::kFamilyCount);

/// F(c) for a run-time lobe.
inline double eval(const Lobe& lobe, double c) noexcept {
  return std::visit([c](const auto& l) { return l(c); }, lobe);
}

inline double at_log_cos(const Lobe& lobe, double u) noexcept {
  return std::visit([u](const auto& l) { return l.at_log_cos(u); }, lobe);
}

/// out[i] = F(c[i]) for i < min(c.size(), out.size()). The per-family loop is what a SIMD
/// back end replaces; the dispatch happens once per batch, not per value.
template <class L, std::floating_point T>
void eval_batch(const L& lobe, std::span<const T> c, std::span<T> out) noexcept {
  const std::size_t count = std::min(c.size(), out.size());
  for (std::size_t i = 0; i < count; ++i) out[i] = lobe(c[i]);
}

inline void eval_batch(const Lobe& lobe, std::span<const double> c, std::span<double> out) noexcept {
  std::visit([&](const auto& l) { eval_batch(l, c, out); }, lobe);
}

}  // namespace specula::lobes
