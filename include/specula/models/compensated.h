#pragma once
// Energy compensation (Kulla & Conty 2017, "Revisiting Physically Based Shading at Imageworks"):
// a model M made to reflect the energy its single-scattering lobe loses, f = f_M + f_ms with
//   f_ms(μ_i, μ_o) = (1 − E(μ_i))(1 − E(μ_o)) / (π (1 − E_avg)),
// E(μ) the directional albedo of M at μ = cos θ and E_avg = 2∫₀¹ E(μ) μ dμ. Its albedo is
// E(μ_i) + (1 − E(μ_i)) = 1 at every angle, up to the error of the table that holds E.
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

  /// True when M loses energy at every node (E ≤ 1 + 1e-7) and on average: then, and only then,
  /// the compensated albedo is 1 within albedo_error.
  bool compensates() const noexcept;

  static double node_mu(std::size_t j) noexcept;
  static double midpoint_mu(std::size_t j) noexcept;  ///< s = (j + ½)/kNodes
  /// E at μ ∈ [0, 1] from the table.
  double at(double mu) const noexcept;
  /// (1 − E(μ_i))₊ (1 − E(μ_o))₊ / (π (1 − E_avg)); 0 when E_avg ≥ 1 (nothing to compensate).
  double multiple_scattering(double mu_i, double mu_o) const noexcept;
};

/// What M+ms is made of: M at its parameter values and M's energy table; f = f_M + f_ms.
struct Compensated {
  std::shared_ptr<const Model> base;
  std::shared_ptr<const EnergyTable> table;
};

/// The suffix that names a compensated model, "+ms".
inline constexpr std::string_view kCompensatedSuffix = "+ms";

/// The id of the model that `id` compensates ("ggx" for "ggx+ms"), or empty if it names none.
std::string_view compensated_base_id(std::string_view id) noexcept;

}  // namespace specula
