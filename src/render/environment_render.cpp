// render_environment (render/environment.h): L_o by multiple importance sampling of the BRDF and of
// the environment, one sample of each per pair, weighted by the power heuristic (Veach 1997 §9.2).
#include <algorithm>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "geometry.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"
#include "specula/render/environment.h"
#include "specula/sampling/sampler.h"
#include "specula/sampling/seeds.h"

namespace specula::render {
namespace {

/// The power heuristic's weight of a sample of density `own` over its rival's `other`, divided
/// by `own`: the factor of the sample's integrand.
double weight_over_pdf(double own, double other) noexcept { return own / (own * own + other * other); }

/// The shading frame of one surface point, as the sampler sees it: N = +z.
struct LocalFrame {
  Frame frame;

  Vec3 to_local(const Vec3& d) const noexcept { return {dot(d, frame.t), dot(d, frame.b), dot(d, frame.w)}; }
  Vec3 to_world(const Vec3& d) const noexcept { return frame.t * d.x + frame.b * d.y + frame.w * d.z; }
};

class EnvironmentShader {
 public:
  EnvironmentShader(const Scene& scene, const Environment& environment)
      : material_(scene.material), environment_(environment), geometry_(scene), sampler_(scene.material.model),
        shadows_(geometry_.casts_shadows()) {}

  Rgb radiance(const Ray& ray, int samples, sampling::SplitMixStream& random) const noexcept {
    const auto hit = geometry_.closest(ray);
    if (!hit) return environment_.radiance(ray.direction);
    const Vec3 v = -ray.direction;
    const LocalFrame local{Frame(hit->normal)};
    const Vec3 v_local = local.to_local(v);
    Rgb sum;
    for (int i = 0; i < samples; ++i) {
      const double u1 = random.uniform(), u2 = random.uniform();
      sum = sum + brdf_sample(*hit, v, local, v_local, u1, u2);
      const double u3 = random.uniform(), u4 = random.uniform();
      sum = sum + environment_sample(*hit, v, local, v_local, u3, u4);
    }
    return material_.ambient_radiance() + sum * (1.0 / samples);
  }

 private:
  /// L_env(ω) (ρ_s f(N, ω, V) + ρ_d/π) cos θ_ω where ω reaches the point; 0 where it is blocked.
  Rgb integrand(const detail::SurfaceHit& hit, const Vec3& l, const Vec3& v, const Rgb& incoming) const noexcept {
    const double cos_l = dot(hit.normal, l);
    if (!(cos_l > 0) || (shadows_ && geometry_.blocked(hit, l, detail::kInfinity))) return {};
    return incoming * material_.brdf(material_.model(hit.normal, l, v)) * cos_l;
  }

  /// ω from the model's sampler with V as its ω_i: density sampler.pdf(V, ω).
  Rgb brdf_sample(const detail::SurfaceHit& hit, const Vec3& v, const LocalFrame& local, const Vec3& v_local, double u1,
                  double u2) const noexcept {
    const sampling::Sample s = sampler_.sample(v_local, u1, u2);
    if (!s.valid()) return {};
    const Vec3 l = local.to_world(s.wo);
    const double weight = weight_over_pdf(s.pdf, environment_.pdf(hit.normal, l));
    return integrand(hit, l, v, environment_.radiance(l)) * weight;
  }

  Rgb environment_sample(const detail::SurfaceHit& hit, const Vec3& v, const LocalFrame& local, const Vec3& v_local,
                         double u1, double u2) const noexcept {
    const EnvironmentSample e = environment_.sample(hit.normal, u1, u2);
    if (!(e.pdf > 0)) return {};
    const double weight = weight_over_pdf(e.pdf, sampler_.pdf(v_local, local.to_local(e.direction)));
    return integrand(hit, e.direction, v, e.radiance) * weight;
  }

  const Material& material_;
  const Environment& environment_;
  detail::Geometry geometry_;
  sampling::Sampler sampler_;
  bool shadows_;
};

void check_settings(const Scene& scene, const RenderSettings& size, const EnvironmentSettings& settings) {
  validate(scene);
  if (!scene.lights.empty())
    throw InvalidArgument("an environment-lit scene has no other lights: the environment is the only light");
  check_samples(size, settings, Spelling::key);
}

}  // namespace

void check_samples(const RenderSettings& size, const EnvironmentSettings& settings, Spelling spelling) {
  const std::string samples = spelled("samples", spelling);
  if (settings.samples < 1 || settings.samples > kMaxEnvironmentSamples)
    throw InvalidField("samples",
                       fmt::format("{} {} is outside [1, {}]", samples, settings.samples, kMaxEnvironmentSamples));
  const auto pixels = std::uint64_t(std::max(0, size.width)) * std::uint64_t(std::max(0, size.height));
  const std::uint64_t total = pixels * std::uint64_t(settings.samples);
  if (total > kMaxEnvironmentImageSamples)
    throw InvalidField("samples", fmt::format("{}x{} pixels with {} {} is {} samples, more than the 2^{} an image "
                                              "may take", size.width, size.height, samples, settings.samples, total,
                                              kMaxEnvironmentImageSamplesLog2));
}

Image render_environment(const Scene& scene, const Environment& environment, const RenderSettings& size,
                         const EnvironmentSettings& settings) {
  check_settings(scene, size, settings);  // before the image: a refused size allocates nothing
  Image image(size.width, size.height);
  const EnvironmentShader shader(scene, environment);
  const detail::PinholeRays rays(scene.camera, size.width, size.height);
  const auto shade_rows = [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      for (int x = 0; x < size.width; ++x) {
        check_interrupt();
        sampling::SplitMixStream random(sampling::stream_key(settings.seed, std::uint64_t(y) * size.width + x));
        image.set(x, y, shader.radiance(rays(x, y), settings.samples, random));
      }
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, size.height), carry_limit(shade_rows));
  return image;
}

}  // namespace specula::render
