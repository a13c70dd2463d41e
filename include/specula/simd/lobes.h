#pragma once
// SIMD batch evaluation of every lobe over arrays of cosines, float and double, with Google
// Highway: compiled for every instruction set Highway targets (AVX-512, AVX2, SSE4, NEON, SVE…)
// and dispatched at run time to the best one the CPU has (docs/simd.md).
//
// Two tiers per lobe:
//   exact  within a few ulp of the scalar double lobe (include/specula/lobes/*.h)
//   fast   cheaper logarithms, exponentials and reciprocals; 1e-4 relative where F ≥ 1e-3
// Each (lobe, tier, lane type) states its bound the way Highway states its math functions,
// and tests/simd enforces exactly that bound against the scalar double lobe at the same (float)
// inputs, over dense and random cosines, n ∈ [1e-3, 1e9] and the edge cases. "ulp" means
// ε = std::numeric_limits<T>::epsilon() of the lane type (2⁻²³ float, 2⁻⁵² double), as a
// relative error. F's peak is F(1) = 1.
//
// The bounds (their types in lobes/simd_bounds.h), with F the scalar double reference and F̃ the
// batch result (ErrorBound::allowed):
//
//   |F̃ − F| ≤ (rel + rel_per_ln·|ln F|)·F + abs   where F ≥ floor
//   |F̃ − F| ≤ abs_below                           where F < floor
//
// The |ln F| term is the amplification of an exponent's rounding (F = e^(ln F)); only the Gauss
// lobe's exact tier in double has it, and its scalar reference has it too (lobes/gauss.h).
// "ULP = k" means rel = k·ε. Each built-in family states its bounds, with how its kernels get
// there, in its definition (include/specula/families/<family>.h, `bounds`); a formula's are:
//
//   formula          exact  Max Error: ULP = 0.5 + 16·2⁻⁵² rel.   ULP = 16 + 4·|ln F| + 4 ulp absolute
//                           (float: the double lanes' result rounded once; user-written copies of
//                           the built-in lobes, measured, simd/formula.h: per-op bounds)
//                    fast   Max Error: 1e-4 relative where F ≥ 1e-3, 1e-6 absolute below (float
//                           lanes, contrib math)                double arrays: as exact
//   (rational lobes and double gauss: relative bounds hold where F ≥ the smallest normal number
//   of the lane type; below it |F̃ − F| ≤ that number.)
//
// Measured maxima over the tests' inputs are in docs/simd.md.
//
// Valid Range: c any value (c ≤ 0 gives 0, c > 1 counts as 1, as the scalar lobes; subnormal c
// included), n ∈ [1e-3, 1e9], s ∈ (0, 1e3] (schlick-modified).
// NaN: NaN in, NaN out, except gauss, which gives 0 like its scalar lobe (it tests c > 0).
#include <concepts>
#include <limits>
#include <span>

#include "specula/lobes/lobes.h"
#include "specula/lobes/simd_bounds.h"

namespace specula::simd {

/// A lobe with its parameters, whatever its scalar type.
struct LobeSpec {
  Family family = Family::power;
  double n = 20;
  double s = 1.25;  ///< schlick-modified only
  /// Family::formula: the lobe, evaluated through the vectorized formula path (simd/formula.h).
  /// It must outlive the spec.
  const lobes::Formula* formula = nullptr;
};

LobeSpec spec_of(const lobes::Lobe& lobe) noexcept;

template <std::floating_point T>
constexpr LobeSpec spec_of(const lobes::Power<T>& l) noexcept { return {Family::power, l.n}; }
template <std::floating_point T>
constexpr LobeSpec spec_of(const lobes::Schlick<T>& l) noexcept { return {Family::schlick, l.n}; }
template <std::floating_point T>
constexpr LobeSpec spec_of(const lobes::SchlickModified<T>& l) noexcept {
  return {Family::schlick_modified, l.n, l.s};
}
template <std::floating_point T>
constexpr LobeSpec spec_of(const lobes::Gauss<T>& l) noexcept { return {Family::gauss, l.n}; }
template <std::floating_point T>
constexpr LobeSpec spec_of(const lobes::Log<T>& l) noexcept { return {Family::log, l.n}; }
inline LobeSpec spec_of(const lobes::Formula& l) noexcept { return {Family::formula, 0, 0, &l}; }

/// out[i] = F(c[i]) for i < min(c.size(), out.size()), at the tier's accuracy (bounds above).
/// Parameters are rounded to the lane type first, as the scalar lobes of that type hold them.
void eval_batch(const LobeSpec& lobe, Tier tier, std::span<const float> c, std::span<float> out) noexcept;
void eval_batch(const LobeSpec& lobe, Tier tier, std::span<const double> c, std::span<double> out) noexcept;

template <class L, std::floating_point T>
void eval_batch(const L& lobe, Tier tier, std::span<const T> c, std::span<T> out) noexcept {
  eval_batch(spec_of(lobe), tier, c, out);
}

/// Vector operations per value of the kernel eval_batch runs for (lobe, tier) on the current
/// target: the kernel's count (kOps in src/simd/kernels-inl.h: one per Highway op that is one
/// arithmetic, compare, select, logic or conversion instruction on AVX2/AVX-512; loads and stores
/// of the arrays not counted) over its lanes. The numerator of the benchmark's compute limit.
/// A formula counts its expression nodes (one operation each, at least).
double ops_per_value(const LobeSpec& lobe, Tier tier, bool single_precision);

/// The bound for lanes of type T that `family` states at `tier` (its families/<family>.h), or a
/// formula's (formula_error_bound).
template <std::floating_point T>
ErrorBound error_bound(Family family, Tier tier) noexcept;

/// Whether eval_batch has a SIMD kernel of its own for `family` at `tier` in both lane types (not
/// the fallback, whose kernel counts no operations; a formula is evaluated by its program).
bool has_kernel(Family family, Tier tier);

}  // namespace specula::simd
