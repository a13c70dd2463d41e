#pragma once
// The vectorized formula path: an expr::Program evaluated with Highway over columns of rows, one
// vector op (or hwy/contrib/math function) per expression node, a chunk of kFormulaRows rows at a
// time so that the columns stay in L1, dispatched at run time like the lobe kernels (simd/lobes.h).
// User-defined lobes (simd::eval_batch of Family::formula) and formula BRDFs (simd/brdf.h) run
// through it; lobes::Formula::eval_batch and expr::Program::evaluate_batch stay the scalar
// reference (libm), bit-identical to the scalar evaluation, for the analysis.
//
// Lanes: the exact tier works in double lanes (float arrays promoted, rounded once at the end);
// the fast tier works in float lanes for float arrays and as the exact tier for double arrays
// (rounding c to float would move c^1e9 by 6 %).
//
// Per op, against std:: in the same lane type (Highway contrib-math style; ULP = ε of the lanes,
// tests/simd/formula_test.cpp enforces each over its valid range and the special values):
//
//   Op                         double lanes (exact)           float lanes (fast)
//   + − × ÷ √ |·| neg min max  ULP = 0 (the same IEEE op)     ULP = 0
//   log exp                    ULP = 1                         ULP = 1 (of the float result)
//   log2 log1p sin cos acos asin  ULP = 2                      ULP = 2
//   expm1                      ULP = 3                         ULP = 2
//   pow, uniform integer k:    k = 2: ULP = 0; |k| ≤ 4 (double) or ≤ 32 (float) by
//                              multiplication, ULP = |k| − 1 (x^3 2, x^4 3, x^-3 3, float x^20 19)
//   pow otherwise              ULP = 2                         ULP = 3 + 1.2·|ln pow|
//   (sin, cos: libm per lane beyond |x| > 39000, Highway's range)
//                              (where the result is a normal number; ±0, ±inf, NaN exactly libm's)
//
// Special values are std::'s everywhere (log(0) = −inf, pow(−8, 1/3) = NaN, exp(1000) = +inf…);
// only the magnitude of finite results differs. A whole formula's error is these ops' errors
// carried through the formula, as the scalar evaluation's are: simd/lobes.h states and
// tests/simd enforces the bound over the user-written copies of the built-in lobes.
#include <cstddef>
#include <span>

#include "specula/expr/program.h"
#include "specula/lobes/formula.h"
#include "specula/simd/lobes.h"

namespace specula::simd {

/// Rows per chunk: a program's columns (inputs, lets, stack) of doubles in 2 KiB each.
inline constexpr std::size_t kFormulaRows = 256;

/// The largest |k| of pow(x, k) with a uniform integer k (a constant or parameter) evaluated
/// by multiplication, per lane type.
template <class T>
inline constexpr int kMaxPowChain = sizeof(T) == 8 ? 4 : 32;

/// out[r] = program at row r in double lanes (the exact tier's ops), inputs[i][r] being input i
/// and `params` the parameters in order. Precondition: input_count() inputs and param_count()
/// params, each input at least as long as out.
void eval_program(const expr::Program& program, std::span<const std::span<const double>> inputs,
                  std::span<const double> params, std::span<double> out);
/// The same for float columns at `tier`: exact in double lanes (rounded once), fast in float lanes.
void eval_program(const expr::Program& program, Tier tier, std::span<const std::span<const float>> inputs,
                  std::span<const double> params, std::span<float> out);

/// out[i] = F(c[i]) for i < min(c.size(), out.size()) through the vectorized path at `tier`,
/// with lobes::Formula's conventions: c clamped to 1, F = 0 for c ≤ 0, NaN kept, u = −ln c by the
/// tier's logarithm where the formula reads u.
void eval_formula(const lobes::Formula& lobe, Tier tier, std::span<const float> c, std::span<float> out);
void eval_formula(const lobes::Formula& lobe, Tier tier, std::span<const double> c, std::span<double> out);

}  // namespace specula::simd
