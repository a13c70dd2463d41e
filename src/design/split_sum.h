#pragma once
// The split-sum terms of image-based lighting (Karis 2013): with Schlick's Fresnel F = F0 + (1 −
// F0)·w, w = (1 − V·H)⁵, a microfacet BRDF's directional albedo is E(μ) = F0·A(μ) + B(μ), where
//   A = ∫ f₁ (1 − w) (N·L) dω_L  and  B = ∫ f₁ w (N·L) dω_L,  f₁ the BRDF with F = 1,
// functions of μ = N·V and the perceptual roughness r (α = r², as Unreal and Filament use it).
// Each is tabulated once per process from specula's cubature (analysis::albedo: ggx-schlick with
// F0 = 1, F90 = 0 for A and F0 = 0, F90 = 1 for B) and interpolated bicubically.
#include <span>
#include <string_view>

namespace specula::design {

/// Which of the two.
enum class SplitSumPart { a, b };

/// The grid's nodes a side: μ^¼ and √r each at i/48, dense where A and B turn fastest (grazing,
/// and the mirror's narrow lobe); μ = 0 taken at 10⁻⁶ and α below the model's 0.001 at 0.001.
inline constexpr int kSplitSumNodes = 49;

/// A or B of `model` (a microfacet model id with f0, f90 and alpha: "ggx-schlick",
/// "beckmann-schlick") at μ = N·V and roughness r, each clamped to [0, 1]. The first call for a
/// model and part tabulates it (thread-safe; about a second on two cores).
double split_sum(std::string_view model, SplitSumPart part, double mu, double r);

}  // namespace specula::design
