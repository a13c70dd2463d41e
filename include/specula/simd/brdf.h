#pragma once
// SIMD batch evaluation of whole models, f(N, L, V), over directions held as structure of arrays:
// lobe models (k·F of the form's cosine, through the lobe kernels of simd/lobes.h) and the full
// BRDFs (Ward and its two variants, Cook-Torrance 1982 and normalized, GGX, Lambert), in double.
//
// Every operation before a transcendental function is the scalar model's own, in the same order
// and without contraction into FMAs (src/simd/brdf.cpp is compiled with -ffp-contract=off), so the
// cosine a lobe sees and the argument of an exponential are bit-identical to the scalar path's:
//
//   lobe models  exact  Max Error: the lobe's exact bound (simd/lobes.h, double) + ULP = 1 for k
//                fast   Max Error: the lobe's fast bound, relative to k (1e-4 where F ≥ 1e-3)
//   full BRDFs          Max Error: as its family states (families/<family>.h, `bounds`): with one
//                       exponential (Ward, Cook-Torrance) ULP = 4 exact, 2e-6 relative fast;
//                       without (GGX, Lambert) both tiers are the scalar arithmetic (ULP = 2)
//
// "ULP" is ε = 2⁻⁵² relative; the reference is the scalar Model::operator() at the same
// directions. Valid range: unit N, L, V (as the scalar models); f = 0 where N·L ≤ 0 or N·V ≤ 0.
// Float directions are not offered: rounding a cosine near 1 to float moves c^1000 by ~1e-4.
#include <span>

#include "specula/models/model.h"
#include "specula/simd/lobes.h"

namespace specula::simd {

/// Directions as structure of arrays: N_i = (nx[i], ny[i], nz[i]) and likewise L and V. Every
/// span must have the same length.
struct DirectionBatch {
  std::span<const double> nx, ny, nz, lx, ly, lz, vx, vy, vz;

  std::size_t size() const noexcept { return nx.size(); }
};

/// out[i] = model(N_i, L_i, V_i) for i < min(dirs.size(), out.size()), at the tier's accuracy
/// (bounds above). Throws InvalidArgument if the direction spans differ in length.
void eval_batch(const Model& model, Tier tier, const DirectionBatch& dirs, std::span<double> out);

/// Directions as rows, (x, y, z) after (x, y, z), as a C array of shape (count, 3) holds them
/// (NumPy's): L_i = l[3i…3i+2], V_i likewise, N_i likewise or +z (the local frame) when n is empty.
/// l, v and a given n hold 3·count values.
struct DirectionRows {
  std::span<const double> n, l, v;

  std::size_t size() const noexcept { return l.size() / 3; }
};

/// The same values as the columns' eval_batch, bit for bit: the rows become columns a cache-sized
/// chunk at a time (vector deinterleaving), with no copy of the whole input. Throws
/// InvalidArgument unless l and v (and n if given) hold the same multiple of 3 values.
void eval_batch(const Model& model, Tier tier, const DirectionRows& rows, std::span<double> out);

/// The bound above for `model` at `tier`, in simd/lobes.h's form (F = f/k for lobe models):
/// its family's, or 0 for a user's formula BRDF (bit-identical).
ErrorBound error_bound(const Model& model, Tier tier) noexcept;

}  // namespace specula::simd
