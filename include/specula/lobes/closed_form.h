#pragma once
// The lobes' exact normalizing coefficients k in closed form, all under the paper's condition:
// albedo 1 at normal incidence (docs/math.md §1), i.e. k · 2π ∫ F(c(θ_o)) cos θ_o sin θ_o dθ_o = 1
// with L = N. Part of the vocabulary: the families (families/<family>.h) name them as their
// closed forms; normalize::closed_form looks them up by lobe.
#include <cmath>
#include <numbers>

namespace specula::lobes {

/// Phong's c^n in `rv` form: (n + 2)/(2π). Exact.
inline double phong_rv(double n) noexcept { return (n + 2) / (2 * std::numbers::pi); }

/// c^n in `nh` form (Giesen 2009): (n + 2)(n + 4) / (8π (2^(−n/2) + n)). Exact.
inline double blinn_phong_nh(double n) noexcept {
  return (n + 2) * (n + 4) / (8 * std::numbers::pi * (std::exp2(-n / 2) + n));
}

/// Schlick's lobe in `rv` form: 1 / (2π [n² ln n/(n−1)³ − n/(n−1)² − 1/(2(n−1))]) (docs/math.md §2),
/// by a series in 1 − n where that form cancels (|1 − n| ≤ ½).
/// Max error: 2e-15 relative for n ∈ [1e-3, 1e9].
double schlick_rv(double n) noexcept;

/// The log lobe in `rv` form (docs/math.md §4): 1 / (π (1 − e^a/(2 ln 2) (E₁(a) − E₁(4a)))),
/// a = 2 ln 2 / n, evaluated without cancellation for large n (series in a for a ≤ 1).
/// Max error: 1e-14 relative for n ∈ [1e-3, 1e9] (tests hold it to 1e-13 against mpmath).
double log_rv(double n) noexcept;

}  // namespace specula::lobes
