#pragma once
// Energy compensation: a model M made to reflect (some of) the energy its single-scattering lobe
// loses to the bounces it does not follow. Two ways, each named by a suffix of M's id
// (docs/energy-compensation.md, "Every compensation as a model"):
//
// Added (Kulla & Conty 2017, "Revisiting Physically Based Shading at Imageworks"): f = f_M + F_ms f_ms,
//   f_ms(μ_i, μ_o) = (1 − E(μ_i))(1 − E(μ_o)) / (π (1 − E_avg)),
// E(μ) the directional albedo of M with F = 1 at μ = cos θ and E_avg = 2∫₀¹ E(μ) μ dμ. Where F = 1
// its albedo is E(μ_i) + (1 − E(μ_i)) = 1 at every angle, up to the error of the table that holds E.
//   M+ms            what specula ships. For GGX with a Fresnel below 1 the table holds 1 − E_ms,
//                   E_ms the random walk's multiply scattered albedo with Schlick's F0, or for
//                   another Fresnel kind the F0 of the same F_avg (EnergyTable::from_walk;
//                   analysis::ggx_walk_table, walk_equivalent_f0), F_ms = 1: f_ms gives back what
//                   the walk says comes back. For any other model as M+kulla-conty.
//   M+kulla-conty   the table of M with F = 1 and F_ms = F_avg² E_avg / (1 − F_avg (1 − E_avg))
//                   (Kulla & Conty's appendix; OSL's libbsdl).
// Scaled (Turquin 2019, "Practical multiple scattering compensation for microfacet models"):
//   f = f_M · (1 + F_s (1 − E(μ_o)) / E(μ_o)), μ_o = N·V, the viewer's direction, as renderers scale
//   it (Filament's 1 + f0 (1/dfg.y − 1)). These models are not reciprocal; their albedo at θ is the
//   viewer's, V at θ integrated over L (what a furnace render shows): (1 + F_s (1 − E)/E) E_M(θ).
//   M+turquin-f0    F_s = F0 = F(1) (Filament, three.js, Unreal)
//   M+turquin-f     F_s = F(μ_o), M's Fresnel at the viewer's angle (libbsdl)
//   M+turquin-favg  F_s = F_avg = 2∫F(μ)μ dμ (MaterialX)
//   M+cycles        F_s = F_avg E_avg / (1 − F_avg (1 − E_avg)) (Cycles' microfacet_ggx_preserve_energy)
// A model without a Fresnel (a lobe, a user's formula) has F ≡ 1 in each.
// The catalogue resolves "M+SUFFIX" for any model id M (catalogue/catalogue.h); the table is built by
// the cubature (analysis/energy.h) on first use and cached per model and parameter values.
// A Model holds one as its implementation and hands it out through Model::compensated().
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "specula/brdf/fresnel.h"

namespace specula {

class Model;

/// E(μ) on a grid in s = μ^(1/3), which crowds the nodes toward grazing (μ = 0), where albedos
/// bend most: nodes at s_j = (j + 1)/kNodes (μ = 1 is the last), linear in s between them and
/// extrapolated linearly below the first (μ < 1/kNodes³ ≈ 4e-6).
struct EnergyTable {
  static constexpr std::size_t kNodes = 64;

  std::vector<double> e;            ///< E at node_mu(j), j < kNodes
  double e_avg = 0;                 ///< 2∫₀¹ E(μ) μ dμ by adaptive quadrature of the cubature's E
  double e_avg_error = 0;           ///< the quadrature's error estimate
  double interpolation_error = 0;   ///< max |at(μ) − E(μ)| over the midpoints s = (j + ½)/kNodes
  /// 2∫₀¹ (1 − at(μ))₊ μ dμ / (1 − E_avg), exactly (the interpolant is piecewise polynomial in s):
  /// the albedo of f_ms is (1 − at(μ_i))₊ · ms_scale, which is 1 − at(μ_i) within the table error.
  double ms_scale = 0;
  /// The stated bound on |ρ − 1| of the compensated model, ρ = E + (1 − at(μ))₊ · ms_scale:
  /// 1.5 × its largest measured value over the nodes and the midpoints (the margin covers the
  /// peak of a cell's error lying off its midpoint). Only meaningful where E ≤ 1.
  double albedo_error = 0;
  static constexpr double kErrorMargin = 1.5;
  /// True when 1 − e is the random walk's multiply scattered albedo E_ms (analysis::ggx_walk_table)
  /// rather than M's albedo: f_ms then gives back E_ms itself, Fresnel included.
  bool from_walk = false;

  /// True when M loses energy at every node (E ≤ 1 + 1e-7) and on average: then, and only then,
  /// the compensated albedo is 1 within albedo_error.
  bool compensates() const noexcept;

  static double node_mu(std::size_t j) noexcept;
  static double midpoint_mu(std::size_t j) noexcept;  ///< s = (j + ½)/kNodes
  /// E at μ ∈ [0, 1] from the table.
  double at(double mu) const noexcept;
  /// (1 − E(μ_i))₊ (1 − E(μ_o))₊ / (π (1 − E_avg)); 0 when E_avg ≥ 1 (nothing to compensate).
  double multiple_scattering(double mu_i, double mu_o) const noexcept;
  /// 2∫₀¹ (1 − at(μ))₊ μ dμ over the interpolant, exactly: in s = μ^(1/3) each piece is linear in
  /// s times 6 s⁵ ds, a polynomial of degree 6, which 4-point Gauss-Legendre integrates exactly.
  double lost_average() const noexcept;
};

/// Kulla & Conty 2017's Fresnel of the multiply scattered light, F_avg² E_avg / (1 − F_avg (1 − E_avg)):
/// the share of the white lobe's lost energy 1 − E that leaves the microsurface when every bounce
/// reflects F_avg on average and a bounce leaves with probability E_avg. 1 at F_avg = 1.
double kulla_conty_fresnel(double f_avg, double e_avg) noexcept;

/// Kulla & Conty's F_ms as Cycles scales by it, F_avg E_avg / (1 − F_avg (1 − E_avg)): the Fresnel
/// of the light that leaves after its first bounce (kulla_conty_fresnel is F_avg times it). 1 at
/// F_avg = 1.
double cycles_fresnel(double f_avg, double e_avg) noexcept;

/// Which compensation a suffix names (the header's comment).
enum class CompensationScheme { shipped, kulla_conty, turquin_f0, turquin_f, turquin_favg, cycles };
inline constexpr std::size_t kCompensationSchemeCount = static_cast<std::size_t>(CompensationScheme::cycles) + 1;

/// The suffixes, in CompensationScheme's order: "+ms", "+kulla-conty", …
inline constexpr std::array<std::string_view, kCompensationSchemeCount> kCompensationSuffixes{
    "+ms", "+kulla-conty", "+turquin-f0", "+turquin-f", "+turquin-favg", "+cycles"};

constexpr std::string_view suffix_of(CompensationScheme scheme) noexcept {
  return kCompensationSuffixes[static_cast<std::size_t>(scheme)];
}

/// Whether the scheme scales f_M (Turquin's and Cycles') rather than adding f_ms to it.
constexpr bool scales(CompensationScheme scheme) noexcept {
  return scheme != CompensationScheme::shipped && scheme != CompensationScheme::kulla_conty;
}

/// What a compensated model is made of: M at its parameter values, the energy table and the Fresnel
/// factor of its scheme.
struct Compensated {
  CompensationScheme scheme = CompensationScheme::shipped;
  std::shared_ptr<const Model> base;
  std::shared_ptr<const EnergyTable> table;  ///< E of M with F = 1 (F0 = 1 where M has Schlick's F0), or the walk's
  /// Added schemes: F_ms (kulla_conty_fresnel; 1 where M has no Fresnel). Scaled schemes with a
  /// constant F_s (turquin-f0, turquin-favg, cycles): F_s.
  double fresnel_scale = 1;
  std::optional<fresnel::Channel> fresnel;  ///< turquin-f: M's Fresnel, F_s = F(μ_o); none: F ≡ 1

  /// f from f_M at μ_i = N·L > 0 and μ_o = N·V > 0.
  double apply(double f_m, double mu_i, double mu_o) const noexcept {
    return scales(scheme) ? f_m * scale(mu_o) : f_m + multiple_scattering(mu_i, mu_o);
  }
  /// Scaled schemes: 1 + F_s (1 − E(μ_o)) / E(μ_o).
  double scale(double mu_o) const noexcept;
  /// Added schemes: F_ms f_ms(μ_i, μ_o).
  double multiple_scattering(double mu_i, double mu_o) const noexcept;
  /// The albedo at μ from M's own there: + F_ms (1 − at(μ))₊ ms_scale (added), × scale(μ) (scaled:
  /// the viewer's albedo).
  double albedo(double base_albedo, double mu) const noexcept;
};

/// The suffix that names what specula ships, "+ms".
inline constexpr std::string_view kCompensatedSuffix = kCompensationSuffixes[0];

/// The id of the model that `id` compensates ("ggx" for "ggx+ms" or "ggx+cycles"), or empty if it
/// names none.
std::string_view compensated_base_id(std::string_view id) noexcept;

/// The scheme `id`'s suffix names; shipped when it names none.
CompensationScheme compensation_scheme_of(std::string_view id) noexcept;

}  // namespace specula
