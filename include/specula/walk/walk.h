#pragma once
// The random walk on the Smith microsurface (Heitz, Hanika, d'Eon & Dachsbacher 2016,
// "Multiple-scattering microfacet BSDFs with the Smith model"): the reference that says how much
// energy a rough conductor reflects after 1, 2, 3, … bounces, without bias under the Smith
// assumptions (uncorrelated heights and normals, a uniform height distribution), with the
// Fresnel of every bounce. docs/random-walk.md states the estimators and their checks.
//
// A path enters from above along −ω_i, meets the microsurface at a height drawn from the Smith
// masking function, reflects about a normal drawn from the distribution of visible normals, and
// leaves or meets the surface again. Each bounce's chance to leave is taken in expectation
// (its G₁ at that height), not drawn, so every bounce contributes to its order's albedo; paths
// end by Russian roulette once their weight is small, which keeps the estimate unbiased.
//
// The work is split into blocks of kBlockPaths paths, each drawing from its own seeded stream
// (sampling/seeds.h) and summed in block order: the result depends on the seed and the number of
// paths only, never on the thread count. Within a block the first two bounces are stratified (a
// randomly shifted Sobol' net), which divides the variance of the multiply scattered albedo by
// about 10–30 (docs/random-walk.md); the standard error comes from the spread of the blocks.
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "specula/brdf/fresnel.h"
#include "specula/brdf/vec3.h"

namespace specula::walk {

enum class Distribution { ggx, beckmann };

/// An isotropic microsurface: GGX, D = α²/(π cos⁴θ (α² + tan²θ)²), or Beckmann,
/// D = exp(−tan²θ/α²)/(π α² cos⁴θ), with α ∈ [kMinAlpha, kMaxAlpha].
struct Microsurface {
  Distribution distribution = Distribution::ggx;
  double alpha = 0.5;
  static constexpr double kMinAlpha = 1e-3, kMaxAlpha = 4;
};

/// Paths per block: the unit of work, of seeding, of stratification and of the interrupt checks.
inline constexpr std::uint64_t kBlockPaths = 1024;
/// The fewest paths one estimate may use: 32 blocks, so that their spread is a usable error.
inline constexpr std::uint64_t kMinPaths = 32 * kBlockPaths;
/// The most paths one estimate may use (about a day of one core): larger requests are refused.
inline constexpr std::uint64_t kMaxPaths = std::uint64_t{1} << 36;
/// The orders reported one by one; the last row holds every order from kOrders on.
inline constexpr int kOrders = 4;

/// A Monte Carlo mean and its standard error (the blocks' sample standard deviation over √blocks).
struct Estimate {
  double value = 0, error = 0;
};

/// The directional albedo of one Fresnel channel, split by the number of bounces.
struct Albedo {
  std::array<Estimate, kOrders> order;  ///< 1, 2, 3 bounces, then 4 or more
  Estimate total;                       ///< every order
  Estimate multiple;                    ///< 2 bounces or more: what single scattering misses
};

/// Deliberate faults, for the tests' negative controls only: a correct walk leaves them off.
struct Faults {
  int drop_fresnel_at_bounce = 0;  ///< > 0: that bounce reflects everything (F = 1)
  double masking_alpha_scale = 1;  ///< G₁ (not D) evaluated at α times this
  bool roulette_unweighted = false;  ///< Russian roulette's survivors keep their weight
};

struct Options {
  std::uint64_t paths = std::uint64_t{1} << 20;  ///< rounded up to whole blocks
  std::uint64_t seed = 1;
  /// Called with the fraction done (0–1) after each round of blocks; may be empty.
  std::function<void(double)> progress;
  Faults faults;
};

/// Why the walk cannot run with these values ("" when it can): α outside its range, μ outside
/// (0, 1], a channel outside its domain (analysis/fresnel.h's rules: F0 ∈ [0, 1], η > 0, κ ≥ 0),
/// no channel, or paths outside [kMinPaths, kMaxPaths].
std::string domain_error(const Microsurface& surface, std::span<const fresnel::Channel> channels, double mu,
                         const Options& options);

/// The directional albedo at μ_i = cos θ_i of a conductor whose facets reflect with each of
/// `channels` (one walk: the channels share the paths, so their differences are exact up to the
/// weights). Throws InvalidArgument where domain_error says why; Interrupted when stopped
/// (specula/interrupt), with no partial result.
std::vector<Albedo> conductor_albedo(const Microsurface& surface, std::span<const fresnel::Channel> channels,
                                     double mu, const Options& options);

/// What a rough dielectric interface does with the light of one direction: the share reflected
/// back to its side and the share transmitted to the other, each split by bounce order (a bounce
/// is a reflection or a refraction at a facet). Without absorption they sum to 1: `energy` is
/// their sum, with its own standard error (the two are anti-correlated, so it is far below theirs).
struct DielectricAlbedo {
  Albedo reflection, transmission, energy;
};

/// The walk of a rough dielectric interface between two media, light incident at μ_i = cos θ_i
/// from above, η = n_below / n_above (η < 1: from the denser side, where total internal
/// reflection happens), the exact dielectric Fresnel at every facet from either side (Heitz et al.
/// 2016, §6). Throws as conductor_albedo does (η ∈ [1e-3, 1e3]).
DielectricAlbedo dielectric_albedo(const Microsurface& surface, double eta, double mu, const Options& options);

/// The BRDF times cos θ_o, f(ω_i, ω_o)·μ_o, split as the albedo is (order 1, 2, 3, ≥ 4, total,
/// 2 or more), estimated by next-event estimation toward ω_o at every bounce. ω_i and ω_o are
/// unit vectors above the surface (z > 0). Throws as conductor_albedo does.
std::vector<Albedo> conductor_brdf_cos(const Microsurface& surface, std::span<const fresnel::Channel> channels,
                                       const Vec3& wi, const Vec3& wo, const Options& options);

}  // namespace specula::walk
