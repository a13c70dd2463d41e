#pragma once
// Energy conservation, reciprocity and non-negativity of a model (docs/math.md §1), and the strict
// normalization that the energy check makes possible.
#include <cstdint>
#include <vector>

#include "specula/models/model.h"

namespace specula::analysis {

struct MaxAlbedo {
  double value = 0;
  double theta_deg = 0;
};

/// max over θ_i ∈ [0°, 90°) of ρ(θ_i): ρ on a grid of `step_deg` plus 89.5° and 89.9° (where
/// grazing behaviour shows), then golden-section refinement (to 1e-4°) around the largest sample,
/// unless it is 89.9° (the albedo still rising towards grazing) or a stationary maximum at 0°.
MaxAlbedo max_albedo(const Model& model, double step_deg = 1,
                     const std::vector<double>& grazing_deg = {89.5, 89.9});

struct CheckOptions {
  std::size_t reciprocity_pairs = 10'000;
  std::uint64_t seed = 1;
  double grid_step_deg = 1;
  std::vector<double> grazing_deg{89.5, 89.9};
  /// ρ ≤ 1 + tolerance counts as conserving (the cubature holds 8+ digits).
  double energy_tolerance = 1e-7;
  /// max |f(l,v) − f(v,l)| / max(f(l,v), f(v,l)) allowed.
  double reciprocity_tolerance = 1e-9;
};

struct CheckResult {
  double albedo_normal = 0;
  MaxAlbedo max_albedo;
  double max_asymmetry = 0;      ///< worst relative |f(l,v) − f(v,l)| over the pairs
  std::size_t pairs = 0;
  double min_value = 0;          ///< smallest f seen over the pairs
  /// M+ms (models/compensated.h): its table's stated albedo error (EnergyTable::albedo_error), which the energy verdict
  /// allows beyond energy_tolerance, and max |ρ − 1| over the θ_i grid. 0 for other models.
  double compensation_error = 0;
  double max_deviation_from_one = 0;
  bool conserves_energy = false;
  bool reciprocal = false;
  bool non_negative = false;

  bool all_hold() const noexcept { return conserves_energy && reciprocal && non_negative; }
};

CheckResult check(const Model& model, const CheckOptions& options = {});

/// The coefficient k for which max over θ_i of ρ = 1 (lobe models; the model's own k is
/// ignored). The paper's condition, ρ(0) = 1, is normalize::coefficient.
double strict_coefficient(const Model& lobe_model, double step_deg = 1);

}  // namespace specula::analysis
