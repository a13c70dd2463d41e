#pragma once
// Constant snapping (docs/fit.md, "Constant snapping"): each fitted constant of a formula is tried
// as a simple number — 0, an integer, p/q with q ≤ 12, or p·s/q for s = π, e, ln 2, √2, √3 and
// q ∈ {1, 2, 3, 4, 6} — the
// simplest first; a snapped constant is kept (exact, expr::exact_constant, and held fixed from then
// on) when, with the formula's other constants refitted, its error stays within the tolerance.
// Multiples of the symbols are tried only in a formula that fits to rounding or the target error.
// First, a constant the others make up for (a scale the fit leaves free: a·x/(b·x − c)) is held
// at ±1, the one of them that leaves the most others at simple numbers.
#include <functional>
#include <vector>

#include "constants.h"
#include "genome.h"

namespace specula::fit {

struct SnapSettings {
  Metric metric = Metric::rms;
  Constants constants = Constants::fitted;
  /// A snap is kept while the loss stays at most (1 + tolerance)·(the unsnapped loss), or at most
  /// `floor` (rounding, or the search's target error).
  double tolerance = 0.01;
  double floor = 0;
  /// Asked before each try: true ends the snapping there (a cancel, a stop request).
  std::function<bool()> stop = [] { return false; };
  /// The most refits one formula may take (each fits its constants to every row once).
  int max_refits = 500;
  /// Whether a refitted formula may be kept (the search's: no fit by cancellation of huge constants).
  std::function<bool(const Genome&)> acceptable = [](const Genome&) { return true; };
};

/// The simple numbers near `value` a snap tries, simplest first: 0; the nearest integer; p/q for
/// q = 2 … 12; then p·s/q for each symbol and q = 1, 2, 3, 4, 6 — each within 2 % of `value` (0
/// always).
std::vector<expr::Node> snap_candidates(double value);

struct Snapped {
  Genome genome;
  double loss = 0;
};

/// `g` (fitted) with its constants snapped where the loss allows, the others refitted; `g` as it
/// is, with its loss, where no snap is kept.
Snapped snapped(const Genome& g, const Rows& rows, const SnapSettings& settings);

/// The loss of `g` after fitting its constants that are not exact (exact ones are held fixed).
Snapped refitted(Genome g, const Rows& rows, const SnapSettings& settings);

}  // namespace specula::fit
