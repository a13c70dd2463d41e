#pragma once
// Energy compensation (Kulla & Conty 2017, "Revisiting Physically Based Shading at Imageworks"):
// a model M made to reflect the energy its single-scattering lobe loses, f = f_M + F_ms f_ms with
//   f_ms(μ_i, μ_o) = (1 − E(μ_i))(1 − E(μ_o)) / (π (1 − E_avg)),
// E(μ) the directional albedo of M with F = 1 at μ = cos θ and E_avg = 2∫₀¹ E(μ) μ dμ. Where F = 1
// its albedo is E(μ_i) + (1 − E(μ_i)) = 1 at every angle, up to the error of the table that holds
// E. Where M has a Fresnel below 1 (the built-in microfacet models' F0): for GGX the table holds
// 1 − E_ms, E_ms the random walk's multiply scattered albedo with that Fresnel (EnergyTable::
// from_walk; analysis::ggx_walk_table), so f_ms gives back exactly what the walk says comes back;
// for the others the table is M's with F = 1 and F_ms = F_avg² E_avg / (1 − F_avg (1 − E_avg))
// (Kulla & Conty's appendix), whose error against the walk `specula verdict` measures
// (docs/energy-compensation.md).
// The model id is "M+ms" for any model id M (catalogue/catalogue.h resolves it); the table is built
// by the cubature (analysis/energy.h) on first use and cached per model and parameter values.
// A Model holds one as its implementation and hands it out through Model::compensated().
// docs/energy-compensation.md.
#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>


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

/// What M+ms is made of: M at its parameter values, the energy table of M with F = 1 and the
/// Fresnel factor F_ms; f = f_M + F_ms f_ms.
struct Compensated {
  std::shared_ptr<const Model> base;
  std::shared_ptr<const EnergyTable> table;  ///< E of M with F = 1 (F0 = 1 where M has Schlick's F0)
  double fresnel_scale = 1;                  ///< F_ms (kulla_conty_fresnel); 1 where M has no Fresnel

  /// F_ms f_ms(μ_i, μ_o).
  double multiple_scattering(double mu_i, double mu_o) const noexcept;
  /// The albedo of F_ms f_ms at μ_i: F_ms (1 − at(μ_i))₊ ms_scale.
  double multiple_albedo(double mu_i) const noexcept;
};

/// The suffix that names a compensated model, "+ms".
inline constexpr std::string_view kCompensatedSuffix = "+ms";

/// The id of the model that `id` compensates ("ggx" for "ggx+ms"), or empty if it names none.
std::string_view compensated_base_id(std::string_view id) noexcept;

}  // namespace specula
