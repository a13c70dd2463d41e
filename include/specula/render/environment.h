#pragma once
// Environment lighting (docs/render.md, "Environment lighting"): light arriving from every
// direction at infinity, either uniform (the white furnace) or a latitude-longitude HDR probe,
// and the renderer that integrates it over each visible surface point by multiple importance
// sampling of the material's BRDF and of the environment.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "specula/render/image.h"
#include "specula/render/render.h"
#include "specula/render/scene.h"

namespace specula::render {

/// A direction drawn from an environment, with the radiance arriving from it and its density
/// per solid angle (pdf = 0: no sample).
struct EnvironmentSample {
  Vec3 direction;  ///< unit, toward the light
  Rgb radiance;
  double pdf = 0;
};

/// The radiance L_env(ω) arriving from each direction ω (unit, pointing away from the scene).
///
/// A latitude-longitude map of W×H pixels, y up: row 0 looks straight up (+y), row H − 1 straight
/// down; the centre column looks toward −z (away from the default camera, which sits on +z), and
/// columns to its right turn toward +x, so the map reads as a panorama seen from inside. Pixel
/// (x, y) covers θ ∈ [y, y + 1)·π/H from +y and φ ∈ [x, x + 1)·2π/W − π from −z toward +x:
/// ω = (sin θ sin φ, cos θ, −sin θ cos φ). Radiance is constant over a pixel (nearest pixel).
/// Sampled in proportion to luminance × sin θ: a row by the marginal distribution, then a column
/// by the row's conditional one, then uniformly in (φ, θ) within the pixel (pbrt 3rd ed. §14.2.4).
///
/// A uniform environment is sampled cosine-weighted about the surface normal instead: the light
/// is the same from everywhere, so only the cosine factor of the integrand varies.
class Environment {
 public:
  /// The same radiance from every direction; `uniform({1, 1, 1})` is the white furnace.
  static Environment uniform(const Rgb& radiance);
  /// Throws InvalidArgument for a negative or non-finite sample (naming the pixel).
  static Environment lat_long(const Image& map);

  Rgb radiance(const Vec3& direction) const noexcept;
  /// A direction from two uniform numbers in [0, 1); `normal` (unit) matters to a uniform one only.
  EnvironmentSample sample(const Vec3& normal, double u1, double u2) const noexcept;
  /// The density sample() draws `direction` with at a surface of normal `normal`.
  double pdf(const Vec3& normal, const Vec3& direction) const noexcept;

  bool is_uniform() const noexcept { return width_ == 0; }

 private:
  Environment() = default;
  std::size_t pixel_of(const Vec3& direction) const noexcept;
  Rgb pixel(std::size_t index) const noexcept;

  Rgb constant_;
  int width_ = 0, height_ = 0;
  std::vector<float> samples_;      ///< the map's r, g, b
  std::vector<double> row_cdf_;     ///< marginal: H + 1 entries, 0 … 1
  std::vector<double> column_cdf_;  ///< conditional: H rows of W + 1 entries, 0 … 1
  double mean_weight_ = 0;          ///< the mean of luminance × sin θ over the pixels
};

/// read_image (EXR or PNG) of `path` as a lat_long environment; InvalidArgument when it cannot be
/// read or has a bad sample.
Environment read_environment(const std::filesystem::path& path);

/// The most sample pairs per pixel, and per image (width·height·samples): 2^26 pairs (1024² at the
/// default 64, 256² at 1024) take about 70 s on a loaded 2-core machine (docs/robustness.md).
inline constexpr int kMaxEnvironmentSamples = 1 << 16;
inline constexpr int kMaxEnvironmentImageSamplesLog2 = 26;
inline constexpr std::uint64_t kMaxEnvironmentImageSamples = std::uint64_t{1} << kMaxEnvironmentImageSamplesLog2;

/// How each pixel's integral over the environment is estimated (BRDF Explorer's choices for its
/// lit-object view). Each sample draws two directions whatever the estimator, so that equal sample
/// counts cost the same:
///   uniform      both uniform on the hemisphere about N (no importance sampling), pdf 1/(2π)
///   environment  both from the environment (light importance sampling)
///   brdf         both from the material's BRDF (BRDF importance sampling): the diffuse part's cosine
///                lobe or the model's sampler, chosen by their albedos' shares
///   mis          one of each, combined by the power heuristic (β = 2, Veach 1997 §9.2)
/// Each is unbiased; they differ in noise, which is what the lab's view shows.
enum class EnvironmentEstimator { uniform, environment, brdf, mis };
inline constexpr std::size_t kEnvironmentEstimatorCount = static_cast<std::size_t>(EnvironmentEstimator::mis) + 1;

constexpr const char* to_string(EnvironmentEstimator e) noexcept {
  switch (e) {
    case EnvironmentEstimator::uniform: return "uniform";
    case EnvironmentEstimator::environment: return "environment";
    case EnvironmentEstimator::brdf: return "brdf";
    case EnvironmentEstimator::mis: return "mis";
  }
  return "";
}
static_assert(names_complete<EnvironmentEstimator, kEnvironmentEstimatorCount>([](EnvironmentEstimator e) { return to_string(e); }));

struct EnvironmentSettings {
  int samples = 64;        ///< per pixel, each of two directions (see EnvironmentEstimator)
  std::uint64_t seed = 0;  ///< the pixel's random numbers depend on (seed, pixel index) alone
  EnvironmentEstimator estimator = EnvironmentEstimator::mis;
};

/// InvalidField "samples" for samples outside [1, kMaxEnvironmentSamples] or beyond
/// kMaxEnvironmentImageSamples at `size`, the field spelled as `spelling` says (render_environment
/// checks with Spelling::key; an interface checks first to name its own option).
void check_samples(const RenderSettings& size, const EnvironmentSettings& settings, Spelling spelling);

/// The linear radiance image of `scene` lit by `environment` alone (the scene's lights must be
/// empty). Per pixel, the nearest surface along the ray through its centre shows
///   L_o(V) = ambient·ρ_d + ∫ L_env(ω) (ρ_s f(N, ω, V) + ρ_d/π) cos θ_ω vis(ω) dω,
/// estimated from `samples` pairs of directions drawn as settings.estimator says; with mis (the
/// default) one sample of the model's sampler (sampling::Sampler, drawn with V as its ω_i, weighted
/// by its pdf(V, ω); f(N, L = ω, V) evaluated as such) and one of the environment, combined by the
/// power heuristic (β = 2, Veach 1997 §9.2). vis(ω) = 0 where the
/// scene blocks ω (the renderers' shadow rays); a ray that hits nothing shows L_env of its
/// direction. Deterministic for a seed and bit-identical for any thread count. Throws
/// InvalidArgument for a bad size or scene, lights in it, or samples outside
/// [1, kMaxEnvironmentSamples] or beyond kMaxEnvironmentImageSamples in all.
Image render_environment(const Scene& scene, const Environment& environment, const RenderSettings& size,
                         const EnvironmentSettings& settings);

}  // namespace specula::render
