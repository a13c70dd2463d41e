#pragma once
// Energy tables: the directional albedo E(μ) (μ = cos θ_i) and its cosine-weighted average
// E_avg = 2∫₀¹ E(μ) μ dμ, by the deterministic cubature of analysis/albedo.h (≥ 8 digits) — for
// `specula lut` (a 2D table E(μ, p) over a parameter p) and for the compensated models "M+ms"
// (models/compensated.h), whose 1D table is built here on first use and cached.
// docs/energy-compensation.md.
#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "specula/analysis/albedo.h"
#include "specula/models/compensated.h"
#include "specula/models/model.h"

namespace specula::analysis {

/// E(μ) = ρ(acos μ). Throws InvalidArgument unless kMinMu ≤ μ ≤ 1.
Albedo albedo_at_mu(const Model& model, double mu);
/// The smallest μ taken (θ_i = 89.99999994°): below it acos(μ) rounds toward 90°.
inline constexpr double kMinMu = 1e-9;

/// E_avg = 2∫₀¹ E(μ) μ dμ = 6∫₀¹ E(s³) s⁵ ds by adaptive Gauss-Kronrod in s = μ^(1/3) (smooth
/// where E bends near grazing): ≥ 8 digits, as E itself. Sequential; ~100-250 albedos. For M+ms:
/// E_avg of M plus the multiple-scattering lobe's average, exact from M's table.
Albedo average_albedo(const Model& model);

/// The energy table of `base` (EnergyTable: nodes and midpoints in parallel, the measured
/// interpolation error, and E_avg by adaptive Simpson in s with Richardson's correction, to 1e-7,
/// from panels whose points are those nodes and midpoints, halved where that is not enough, each
/// level's new points in parallel), deterministic for any thread count. `evaluations`, if given,
/// receives the integrand evaluations of all its albedos.
EnergyTable energy_table(const Model& base, std::size_t* evaluations = nullptr);
/// energy_table(base), made once per model (id, origin, parameter values, form, k) and kept.
std::shared_ptr<const EnergyTable> cached_energy_table(const Model& base);
/// Forgets the cached tables (the registry does when user models are cleared).
void clear_energy_tables();

/// `ggx+ms` at F0 < 1: the table whose 1 − E is the random walk's multiply scattered albedo
/// E_ms(μ) of GGX at α with Schlick's F0 (src/analysis/ggx_walk_ms.inc, made by
/// scripts/make_walk_ms_table), so that f_ms gives back E_ms itself: at the 64 nodes, bilinear
/// in (√α, F0) between the walk's; E_avg = 1 − 2∫E_ms μ dμ exactly, so ms_scale = 1;
/// interpolation_error and albedo_error the table's stated error against the walk, measured
/// midway between its nodes. α ∈ [1e-3, 1] and F0 ∈ [0, 1] (clamped to them).
EnergyTable ggx_walk_table(double alpha, double f0);

/// The F0 of ggx_walk_table that stands for a GGX model with Fresnel `f`: `f`'s own F0 for
/// Schlick's F0 alone (F90 = 1, p = 5); for any other kind, the Schlick F0 with the same F_avg,
/// (21 F_avg − 1)/20 clamped to [0, 1] (F_avg = F0 + (1 − F0)/21). The walk's E_ms follows F_avg
/// closely (docs/energy-compensation.md, "Every Fresnel kind": the dielectric η = 1.5 at
/// F0 = 0.0466 within 10⁻⁴, metals within the verdict's figures).
double walk_equivalent_f0(const fresnel::Channel& f);

/// The documented size of a table (docs/robustness.md, measured): 65536 cells of Cook-Torrance,
/// the costliest built-in albedo, take about a minute on two idle cores; an E_avg costs 100-400
/// cells, so at most 256 of them. Every interface (specula lut, import specula) keeps to these.
inline constexpr std::size_t kMaxLutAxisValues = 1024, kMaxLutCells = 65'536, kMaxLutAverages = 256;

/// Called as cells finish (from any thread, one call at a time): cells done, cells in all.
using Progress = std::function<void(std::size_t done, std::size_t total)>;
/// The model at parameter value p.
using ModelAt = std::function<Model(double p)>;

/// E(μ, p) on a grid, row-major in p (e[i * mu.size() + j] = E(mu[j], p[i])), and E_avg(p).
struct AlbedoLut {
  std::vector<double> p, mu;
  std::vector<double> e;
  std::vector<double> e_avg;  ///< one per p, or empty
  /// How the lookups interpolate: linearly in p^(1/p_power) and μ^(1/mu_power) (1: in p and μ;
  /// 2: in √p, for an axis spaced so, io::spacing_power).
  double p_power = 1, mu_power = 1;

  double at(std::size_t i, std::size_t j) const noexcept { return e[i * mu.size() + j]; }
  /// Bilinear interpolation of E at (μ, p) inside the grid (linear along an axis of one value).
  double bilinear(double mu_value, double p_value) const noexcept;
  /// Linear interpolation of E_avg at p. Precondition: e_avg not empty.
  double linear_e_avg(double p_value) const noexcept;
};

/// Every cell in parallel (oneTBB; each cell lands at its index: the table does not depend on the
/// thread count), the E_avg in parallel over p when `average`. Throws Interrupted when stopped.
AlbedoLut albedo_lut(const ModelAt& model_at, std::span<const double> p, std::span<const double> mu,
                     bool average, const Progress& progress = {});

/// The table's interpolation error against the cubature: max |bilinear − E| at the centres of the
/// cells (at the midpoints of the one axis that has more than one value), and max |linear − E_avg|
/// at the midpoints of p when the table has E_avg (else 0); centres and midpoints in the
/// coordinates the lookup interpolates in (p_power, mu_power).
struct LutError {
  double e = 0;
  double e_avg = 0;
};
LutError lut_interpolation_error(const AlbedoLut& lut, const ModelAt& model_at, const Progress& progress = {});

/// The model at a second parameter's value q: the ModelAt of that slice.
using SliceAt = std::function<ModelAt(double q)>;
/// A table over a second parameter q, one AlbedoLut per value of q (all on one (p, μ) grid),
/// looked up trilinearly (linearly in q^(1/q_power) between two slices' bilinear values), E_avg
/// bilinearly in (p, q): its error against the cubature at the centres of the cells, as above.
LutError lut_interpolation_error(std::span<const AlbedoLut> slices, std::span<const double> q, double q_power,
                                 const SliceAt& slice_at, const Progress& progress = {});

}  // namespace specula::analysis
