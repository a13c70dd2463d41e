#pragma once
// k(p) in closed form for the designed lobes that integrate exactly: polynomials in c, on each
// side of at most one clamp max(α(p)·c + β(p), 0).
#include <optional>
#include <string>

#include "specula/design/design.h"

namespace specula::design {

/// The most nodes of Gauss–Legendre the closed form uses (exact for degree ≤ 2·kMaxNodes − 1).
inline constexpr int kMaxNodes = 8;

/// k of the lobe `formula` (in c and s.param), in the target's form, as a formula in s.param:
/// 1 / ρ₁(0) with the albedo integral (rv: 2π ∫₀¹ F(c) c dc; nh: 2π ∫ from 1/√2 to 1 of
/// F(x)(2x² − 1)4x dx) split at the clamp's kink c₀ = −β/α (clamped to the interval) and each
/// piece by Gauss–Legendre with enough nodes for its degree — exact for polynomials, so the
/// formula is k itself, not an approximation of it. nullopt where F is not such a lobe, α changes
/// sign over the range, or the formula would pass a model file's limits (4096 characters, 64 deep).
std::optional<std::string> closed_form_k(const std::string& formula, const Settings& s);

}  // namespace specula::design
