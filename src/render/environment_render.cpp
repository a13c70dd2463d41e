// render_environment (render/environment.h): L_o by multiple importance sampling of the BRDF and of
// the environment, one sample of each per pair, weighted by the power heuristic (Veach 1997 §9.2).
#include <algorithm>
#include <cmath>
#include <numbers>
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
  EnvironmentShader(const Scene& scene, const Environment& environment, EnvironmentEstimator estimator)
      : material_(scene.material), environment_(environment), geometry_(scene), sampler_(scene.material.model),
        shadows_(geometry_.casts_shadows()), estimator_(estimator) {}

  Rgb radiance(const Ray& ray, int samples, sampling::SplitMixStream& random) const noexcept {
    const auto hit = geometry_.closest(ray);
    if (!hit) return environment_.radiance(ray.direction);
    const LocalFrame local{Frame(hit->normal)};
    const Point at{*hit, -ray.direction, local, local.to_local(-ray.direction)};
    Rgb sum;
    for (int i = 0; i < samples; ++i) {
      const double u1 = random.uniform(), u2 = random.uniform(), u3 = random.uniform(), u4 = random.uniform();
      sum = sum + sample_pair(at, u1, u2, u3, u4);
    }
    return material_.ambient_radiance() + sum * (1.0 / samples);
  }

 private:
  struct Point {
    const detail::SurfaceHit& hit;
    Vec3 v;
    LocalFrame local;
    Vec3 v_local;
  };

  /// Two directions' contributions as the estimator draws them (their sum estimates twice the integral
  /// for the single-strategy estimators, once for MIS's pair).
  Rgb sample_pair(const Point& p, double u1, double u2, double u3, double u4) const noexcept {
    switch (estimator_) {
      case EnvironmentEstimator::uniform: return (uniform_sample(p, u1, u2) + uniform_sample(p, u3, u4)) * 0.5;
      case EnvironmentEstimator::environment:
        return (environment_only(p, u1, u2) + environment_only(p, u3, u4)) * 0.5;
      case EnvironmentEstimator::brdf: return (brdf_only(p, u1, u2) + brdf_only(p, u3, u4)) * 0.5;
      case EnvironmentEstimator::mis: break;
    }
    return brdf_sample(p, u1, u2) + environment_sample(p, u3, u4);
  }

  /// L_env(ω) (ρ_s f(N, ω, V) + ρ_d/π) cos θ_ω where ω reaches the point; 0 where it is blocked.
  Rgb integrand(const detail::SurfaceHit& hit, const Vec3& l, const Vec3& v, const Rgb& incoming) const noexcept {
    const double cos_l = dot(hit.normal, l);
    if (!(cos_l > 0) || (shadows_ && geometry_.blocked(hit, l, detail::kInfinity))) return {};
    return incoming * material_.brdf(material_.model(hit.normal, l, v)) * cos_l;
  }

  /// ω uniform on the hemisphere about N: density 1/(2π).
  Rgb uniform_sample(const Point& p, double u1, double u2) const noexcept {
    const double z = u1, r = std::sqrt(std::max(0.0, 1 - z * z)), phi = 2 * std::numbers::pi * u2;
    const Vec3 l = p.local.to_world({r * std::cos(phi), r * std::sin(phi), z});
    return integrand(p.hit, l, p.v, environment_.radiance(l)) * (2 * std::numbers::pi);
  }

  Rgb environment_only(const Point& p, double u1, double u2) const noexcept {
    const EnvironmentSample e = environment_.sample(p.hit.normal, u1, u2);
    if (!(e.pdf > 0)) return {};
    return integrand(p.hit, e.direction, p.v, e.radiance) * (1 / e.pdf);
  }

  /// The material's BRDF sampled as a one-sample mixture: the diffuse part's cosine lobe with the
  /// diffuse share of the albedos (their channel means), else the model's sampler; the density is
  /// the mixture's, so that directions only the diffuse part reflects are covered as well.
  Rgb brdf_only(const Point& p, double u1, double u2) const noexcept {
    const double share = diffuse_share();
    Vec3 local_l;
    if (u1 < share) {
      const double u = u1 / share, r = std::sqrt(u), phi = 2 * std::numbers::pi * u2;
      local_l = {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u))};
    } else {
      const sampling::Sample s = sampler_.sample(p.v_local, (u1 - share) / (1 - share), u2);
      if (!s.valid()) return {};
      local_l = s.wo;
    }
    const double pdf = share * std::max(0.0, local_l.z) / std::numbers::pi +
                       (1 - share) * sampler_.pdf(p.v_local, local_l);
    if (!(pdf > 0)) return {};
    const Vec3 l = p.local.to_world(local_l);
    return integrand(p.hit, l, p.v, environment_.radiance(l)) * (1 / pdf);
  }

  double diffuse_share() const noexcept {
    const auto mean = [](const Rgb& c) { return (c.r + c.g + c.b) / 3; };
    const double d = mean(material_.diffuse), s = mean(material_.specular);
    return d + s > 0 ? d / (d + s) : 0;
  }

  /// ω from the model's sampler with V as its ω_i: density sampler.pdf(V, ω), MIS-weighted.
  Rgb brdf_sample(const Point& p, double u1, double u2) const noexcept {
    const sampling::Sample s = sampler_.sample(p.v_local, u1, u2);
    if (!s.valid()) return {};
    const Vec3 l = p.local.to_world(s.wo);
    const double weight = weight_over_pdf(s.pdf, environment_.pdf(p.hit.normal, l));
    return integrand(p.hit, l, p.v, environment_.radiance(l)) * weight;
  }

  Rgb environment_sample(const Point& p, double u1, double u2) const noexcept {
    const EnvironmentSample e = environment_.sample(p.hit.normal, u1, u2);
    if (!(e.pdf > 0)) return {};
    const double weight = weight_over_pdf(e.pdf, sampler_.pdf(p.v_local, p.local.to_local(e.direction)));
    return integrand(p.hit, e.direction, p.v, e.radiance) * weight;
  }

  const Material& material_;
  const Environment& environment_;
  detail::Geometry geometry_;
  sampling::Sampler sampler_;
  bool shadows_;
  EnvironmentEstimator estimator_;
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
  const EnvironmentShader shader(scene, environment, settings.estimator);
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
