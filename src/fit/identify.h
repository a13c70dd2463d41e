#pragma once
// Elementary constants recognised from their value (docs/fit.md, "Elementary constants"): a fitted
// constant of a formula that fits to rounding is tried as a closed form found by an integer
// relation (PSLQ, Ferguson & Bailey 1999, as mpmath's identify() and SymPy's nsimplify use it):
//   products of powers  |v|^d = 2^a · 3^b · 5^c · 7^f · π^g · e^h   (e^(−1/2), 1/√(2π), √(3/2), π²)
//   logarithms          d·v = a·ln 2 + b·ln 3 + c·ln 5 + f·ln 7     (ln 3, ln(3/2)/2)
// with small integers (d ≤ 6, |a| … |h| ≤ 12). Double precision bounds what a relation can prove:
// a candidate is offered only within 1e-9 (relative) of the value, and kept only when the refitted
// formula still fits to rounding (snap.cpp), which a wrong closed form does not.
#include <optional>
#include <span>
#include <vector>

#include "genome.h"

namespace specula::fit {

/// A small integer relation a with a·x ≈ 0 (|a·x| ≤ tolerance · |x|, |a_i| ≤ max_coefficient),
/// found by PSLQ in double precision; nothing when PSLQ proves every relation larger than that, or
/// x has fewer than 2 or more than 12 entries, a non-finite one, or a zero.
std::optional<std::vector<long long>> integer_relation(std::span<const double> x, long long max_coefficient,
                                                       double tolerance);

/// The rational p/q within 1e-9 (relative) of `value` with the smallest q ≤ 255 (|p| ≤ 32767, what
/// an exact constant holds), from its continued fraction: 1/30 for 0.0333333333, where snapping's
/// q ≤ 12 stops. Nothing for 0, a non-finite value, or none so near.
std::optional<expr::Node> exact_rational(double value);

/// The closed forms near `value` (within 1e-9 relative), simplest first, each a constant-only
/// subtree of exact constants (expr::exact_constant under pow, exp, log) in postfix — none when
/// `value` is 0, not finite, or a simple multiple p/q·s that snap_candidates() already offers.
std::vector<Genome> elementary_constants(double value);

}  // namespace specula::fit
