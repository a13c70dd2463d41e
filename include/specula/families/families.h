#pragma once
// Every built-in model family, in the order models() lists their models: the lobe families in
// lobes::Lobe's (and simd::Family's) order, then the full BRDFs. A family's header,
// families/<name>.h, holds all of it (families/family.h); the registry builds the catalogue from
// this list, and the GLSL emitter, the SIMD bounds, the report and the tests read it.
#include <array>
#include <string_view>

#include "specula/families/beckmann.h"
#include "specula/families/cook_torrance.h"
#include "specula/families/family.h"
#include "specula/families/gauss.h"
#include "specula/families/ggx.h"
#include "specula/families/lambert.h"
#include "specula/families/log.h"
#include "specula/families/power.h"
#include "specula/families/schlick.h"
#include "specula/families/schlick_modified.h"
#include "specula/families/ward.h"

namespace specula::families {

inline constexpr std::array<const Family*, 10> kFamilies{
    &kPower, &kSchlick, &kSchlickModified, &kGauss, &kLog, &kLambert, &kWard, &kCookTorrance, &kGgx, &kBeckmann};

/// The lobe families: the first of kFamilies, one per lobes::Lobe alternative but the last (a
/// user's lobes::Formula, which is no built-in family).
inline constexpr std::size_t kLobeFamilyCount = std::variant_size_v<lobes::Lobe> - 1;

constexpr bool lobe_families_lead_in_simd_order() {
  for (std::size_t i = 0; i < kFamilies.size(); ++i) {
    const bool lobe = i < kLobeFamilyCount;
    if ((kFamilies[i]->kind == ModelKind::lobe) != lobe) return false;
    if (lobe && kFamilies[i]->simd != static_cast<simd::Family>(i)) return false;
  }
  return true;
}
static_assert(lobe_families_lead_in_simd_order(), "kFamilies: the lobe families first, in simd::Family order");

// lobe_family indexes kFamilies by simd::Family: every SIMD family but the last, formula, is one of
// the lobe families that lead kFamilies (checked in order above).
static_assert(static_cast<std::size_t>(simd::Family::formula) == kLobeFamilyCount &&
                  simd::kFamilyCount == kLobeFamilyCount + 1 && kLobeFamilyCount <= kFamilies.size(),
              "kFamilies: one lobe family per simd::Family but formula");

/// The lobe family whose SIMD kernels are `family`. Precondition: family ≠ simd::Family::formula.
constexpr const Family& lobe_family(simd::Family family) noexcept { return *kFamilies[static_cast<std::size_t>(family)]; }

/// The family of the built-in model `id` and the model's definition; nullptr for any other id.
struct BuiltinModel {
  const Family* family = nullptr;
  const ModelDefinition* model = nullptr;
};
constexpr BuiltinModel find_builtin(std::string_view id) noexcept {
  for (const Family* family : kFamilies)
    for (const ModelDefinition& model : family->models)
      if (model.id == id) return {family, &model};
  return {};
}

/// The family of a model from the registry; nullptr for a user-defined model (origin not built-in).
inline const Family* family_of(const ModelInfo& info) noexcept {
  return info.is_builtin() ? find_builtin(info.id).family : nullptr;
}

/// A lobe's family name as tables and the CLI print it: its family's, or "formula" for a user's.
inline std::string_view family_name(const lobes::Lobe& lobe) noexcept {
  return lobe.index() < kLobeFamilyCount ? kFamilies[lobe.index()]->name : "formula";
}

}  // namespace specula::families
