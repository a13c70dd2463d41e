#pragma once
// Which energy compensation is right: the published compensations of a microfacet conductor with
// Fresnel, measured against the random walk on its microsurface (walk/walk.h), the reference
// (docs/energy-compensation.md, "Which compensation is right").
//
// Each compensation adds to the single-scattering lobe f_F (Fresnel F) the energy it misses; its
// directional albedo at μ is a closed form in what a renderer tabulates, E(μ) and E_avg of the
// lobe with F = 1, the lobe's own albedo E_F(μ), and F's values F(μ), F0 = F(1) and
// F_avg = 2∫F(μ)μ dμ. The walk gives the truth, E_F(μ) + E_ms(μ) (its orders 1 and ≥ 2).
#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "specula/brdf/fresnel.h"
#include "specula/io/table.h"
#include "specula/walk/walk.h"

namespace specula::queries {

enum class Compensation {
  none,               ///< f_F alone: loses what single scattering misses
  kulla_conty,        ///< + f_ms · F_avg² E_avg / (1 − F_avg(1 − E_avg)) (Kulla & Conty 2017; libbsdl)
  turquin_f0,         ///< f_F · (1 + F0 (1 − E)/E) (Turquin 2019; Filament, three.js, Unreal)
  turquin_fresnel,    ///< f_F · (1 + F(μ) (1 − E)/E) (libbsdl)
  turquin_average,    ///< f_F · (1 + F_avg (1 − E)/E) (MaterialX)
  cycles,             ///< f_F · (1 + F_ms (1 − E)/E), F_ms = F_avg E_avg / (1 − F_avg(1 − E_avg)) (Cycles)
  /// Fitted here to the walk's cells (docs/energy-compensation.md): + (1 − E) · a · x p/(1 − x(1 − p)),
  /// the first bounce's Fresnel a = max(E_F/E, F_avg), the later bounces' x = (E_F/E + F_avg)/2, and
  /// p = E_avg^0.7 the chance to leave after each of them.
  walk_fit,
  /// What specula ships: `+ms` on the GGX model of the cell's Fresnel (`ggx`, `ggx-f82`,
  /// `ggx-dielectric`, …), whose f_ms gives back the walk's own multiply scattered albedo from a
  /// table, at Schlick's F0 of the same F_avg for the other kinds (models/compensated.h).
  shipped,
};
inline constexpr std::size_t kCompensationCount = 8;
inline constexpr std::array<std::string_view, kCompensationCount> kCompensationNames{
    "none", "kulla-conty", "turquin-f0", "turquin-f", "turquin-favg", "cycles", "walk-fit", "ggx+ms"};

/// What a compensation's albedo is made of at one μ.
struct CompensationInputs {
  double e = 1;      ///< E(μ): the lobe's albedo with F = 1
  double e_avg = 1;  ///< E_avg = 2∫E(μ)μ dμ
  double e_f = 1;    ///< E_F(μ): the lobe's albedo with its Fresnel
  double f_mu = 1;   ///< F(μ)
  double f0 = 1;     ///< F(1)
  double f_avg = 1;  ///< F_avg
  double shipped = std::numeric_limits<double>::quiet_NaN();  ///< ggx+ms's albedo here, where it applies
};

/// The directional albedo of `c` at the inputs' μ (for `shipped`, the inputs' `shipped`).
double compensated_albedo(Compensation c, const CompensationInputs& in) noexcept;

/// A Fresnel the verdict measures, with the family its errors are summarized in.
struct VerdictFresnel {
  std::string family;  ///< "schlick", "dielectric", "gold", …
  std::string label;   ///< the channel as text (catalogue/fresnel_spec.h) or a metal's channel
  fresnel::Channel channel;
};

/// The verdict's Fresnels (issue 39): Schlick at F0 ∈ {0.04, 0.2, 0.5, 0.9}; dielectrics
/// η ∈ {1.1, 1.5, 2.5} (a reflection lobe over an absorbing base: what refracts is lost); gold,
/// copper and aluminium as F82-tint per RGB channel, F0 and tint taken from their complex indices.
std::vector<VerdictFresnel> verdict_fresnels();

struct VerdictSettings {
  walk::Distribution distribution = walk::Distribution::ggx;
  std::vector<double> alpha{0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.85, 1.0};
  std::vector<double> mu{0.05, 0.1, 0.2, 0.35, 0.5, 0.7, 0.85, 1.0};
  std::vector<VerdictFresnel> fresnels = verdict_fresnels();
  std::uint64_t paths = std::uint64_t{1} << 17;  ///< per (α, μ) cell: every Fresnel shares them
  std::uint64_t seed = 1;
  std::function<void(std::size_t done, std::size_t total)> progress;  ///< after each (α, μ) cell
};

/// One compensation's error over a family's cells: |A − truth| (the total and the multiply
/// scattered part differ by the same E_F, so their absolute errors are one number) and its
/// largest share of the truth's multiply scattered part, where that is above 10⁻³.
struct VerdictSummary {
  std::string family;
  Compensation compensation;
  double max_error = 0, rms_error = 0;
  double max_relative_ms = 0;   ///< max |A − truth| / E_ms over cells with E_ms > 1e-3
  double max_walk_error = 0;    ///< the walk's largest standard error on E_ms in these cells
  std::size_t cells = 0;         ///< cells measured (0: the compensation does not apply to the family)
};

struct Verdict {
  io::Table cells;                       ///< a row per (α, μ, Fresnel): inputs, truth, each compensation's albedo
  std::vector<VerdictSummary> summary;   ///< per family and compensation
};

/// Measures every compensation against the walk over the settings' grid. GGX only: E(μ), E_avg
/// come from specula's cubature of the `ggx` model at F0 = 1 (8+ digits); E_F(μ) is the walk's
/// order 1 (whose standard error the table gives). Throws InvalidArgument for an empty grid or
/// values outside the walk's domain; Interrupted when stopped.
Verdict verdict(const VerdictSettings& settings);

/// The summary as a table: family, compensation (index into kCompensationNames), the errors.
io::Table summary_table(const Verdict& v);

}  // namespace specula::queries
