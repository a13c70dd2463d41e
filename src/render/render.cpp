#include "specula/render/render.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <vector>

#include "specula/brdf/directions.h"
#include "specula/interrupt/interrupt.h"
#include "specula/simd/brdf.h"
#include "geometry.h"

namespace specula::render {
namespace {

using detail::Geometry;
using detail::kInfinity;
using detail::PinholeRays;
using detail::SurfaceHit;

struct Incidence {
  Vec3 l;          ///< unit, toward the light
  Rgb irradiance;  ///< E on a surface facing the light
  double distance;
};

// A light with what does not depend on the surface point worked out once.
struct PreparedLight {
  explicit PreparedLight(const Light& light)
      : directional(light.kind == LightKind::directional),
        vector(directional ? normalized(light.direction) : light.position),
        irradiance(light.colour * light.intensity) {}

  Incidence at(const Vec3& point) const noexcept {
    if (directional) return {vector, irradiance, kInfinity};
    const Vec3 to_light = vector - point;
    const double d2 = dot(to_light, to_light), d = std::sqrt(d2);
    return {to_light * (1 / d), irradiance * (1 / d2), d};
  }

  bool directional;
  Vec3 vector;  ///< unit direction toward a directional light; a point light's position
  Rgb irradiance;
};

// docs/math.md §5, the paper's local illumination: the shading equation, written once for both
// render paths (and once in GLSL, src/render/shaders/scene/shading.glsl's scene_surface_radiance):
//   L_o = ambient·ρ_d + Σ over the lights that reach the point of (ρ_d/π + ρ_s f(N, L, V)) · E · N·L,
// summed light by light in scene order, the material's terms as Material::ambient_radiance and
// Material::brdf compute them (render_environment's as well). radiance[j] becomes L_o of surface
// point j; lit(light, add) calls add(j, f, E, N·L) for each point j that `light` reaches.
template <class Lit>
void shade(const Material& m, std::span<const PreparedLight> lights, std::span<Rgb> radiance, Lit&& lit) {
  std::fill(radiance.begin(), radiance.end(), m.ambient_radiance());
  for (const PreparedLight& light : lights)
    lit(light, [&](std::size_t j, double f, const Rgb& irradiance, double cos_i) {
      radiance[j] = radiance[j] + m.brdf(f) * irradiance * cos_i;
    });
}

/// A row's pixels lit by one light, as structure of arrays for the batch BRDF. Sized once per
/// row and filled by index: push_back on a dozen arrays cost more than the lobe saves.
struct LitPixels {
  std::vector<int> pixel;
  std::array<std::vector<double>, 9> dirs;  ///< N, L, V by component
  std::vector<double> cos_i;
  std::vector<Rgb> irradiance;
  std::size_t count = 0;

  void reserve(int width) {
    const auto n = static_cast<std::size_t>(width);
    pixel.resize(n);
    for (auto& d : dirs) d.resize(n);
    cos_i.resize(n);
    irradiance.resize(n);
  }
  void add(int x, const Vec3& n, const Vec3& l, const Vec3& v, double cos, const Rgb& e) {
    const std::size_t j = count++;
    pixel[j] = x;
    const Vec3* vectors[3] = {&n, &l, &v};
    for (std::size_t k = 0; k < 3; ++k) {
      dirs[3 * k][j] = vectors[k]->x;
      dirs[3 * k + 1][j] = vectors[k]->y;
      dirs[3 * k + 2][j] = vectors[k]->z;
    }
    cos_i[j] = cos;
    irradiance[j] = e;
  }
  simd::DirectionBatch batch() const {
    auto first = [&](const std::vector<double>& d) { return std::span<const double>(d.data(), count); };
    return {first(dirs[0]), first(dirs[1]), first(dirs[2]), first(dirs[3]), first(dirs[4]),
            first(dirs[5]), first(dirs[6]), first(dirs[7]), first(dirs[8])};
  }
};

/// What shading a row needs, reused from row to row by one task.
struct RowScratch {
  std::vector<std::optional<SurfaceHit>> hits;
  std::vector<Vec3> view;
  std::vector<Rgb> sums;
  LitPixels lit;
  std::vector<double> f;

  void reset(int width) {
    hits.assign(width, std::nullopt);
    view.resize(width);
    sums.resize(width);  // shade() sets them
    lit.reserve(width);
    f.resize(static_cast<std::size_t>(width));
  }
};

class Shader {
 public:
  explicit Shader(const Scene& scene)
      : scene_(scene), geometry_(scene), lights_(scene.lights.begin(), scene.lights.end()),
        shadows_(geometry_.casts_shadows()) {}

  Rgb radiance(const Ray& ray) const noexcept {
    const auto hit = geometry_.closest(ray);
    return hit ? surface_radiance(*hit, -ray.direction) : scene_.background;
  }

  /// One row, shaded as radiance() shades each pixel, with the BRDF evaluated per light for the
  /// whole row in one SIMD batch (the same sums in the same order; f within a few ulp).
  void shade_row(const PinholeRays& rays, int y, RowScratch& s, Image& image) const {
    const int width = image.width();
    s.reset(width);
    for (int x = 0; x < width; ++x) {
      const Ray ray = rays(x, y);
      s.hits[x] = geometry_.closest(ray);
      s.view[x] = -ray.direction;
    }
    shade(scene_.material, lights_, s.sums, [&](const PreparedLight& light, const auto& add) {
      s.lit.count = 0;
      for (int x = 0; x < width; ++x) {
        if (!s.hits[x]) continue;
        if (const auto in = reaching(*s.hits[x], light))
          s.lit.add(x, s.hits[x]->normal, in->l, s.view[x], in->cos_i, in->irradiance);
      }
      simd::eval_batch(scene_.material.model, simd::Tier::exact, s.lit.batch(), s.f);
      for (std::size_t j = 0; j < s.lit.count; ++j)
        add(static_cast<std::size_t>(s.lit.pixel[j]), s.f[j], s.lit.irradiance[j], s.lit.cos_i[j]);
    });
    for (int x = 0; x < width; ++x) image.set(x, y, s.hits[x] ? s.sums[x] : scene_.background);
  }

 private:
  Rgb surface_radiance(const SurfaceHit& hit, const Vec3& v) const noexcept {
    Rgb sum;
    shade(scene_.material, lights_, {&sum, 1}, [&](const PreparedLight& light, const auto& add) {
      if (const auto in = reaching(hit, light))
        add(0, scene_.material.model(hit.normal, in->l, v), in->irradiance, in->cos_i);
    });
    return sum;
  }

  struct Reaching {
    Vec3 l;
    Rgb irradiance;
    double cos_i;
  };

  /// The light's direction, irradiance and N·L at the hit if it reaches it: N·L > 0 and not in shadow.
  std::optional<Reaching> reaching(const SurfaceHit& hit, const PreparedLight& light) const noexcept {
    const Incidence in = light.at(hit.point);
    const double cos_i = dot(hit.normal, in.l);
    if (cos_i <= 0 || (shadows_ && geometry_.blocked(hit, in.l, in.distance))) return std::nullopt;
    return Reaching{in.l, in.irradiance, cos_i};
  }

  const Scene& scene_;
  Geometry geometry_;
  std::vector<PreparedLight> lights_;
  bool shadows_;
};

}  // namespace

Image render_cpu(const Scene& scene, const RenderSettings& settings) {
  Image image(settings.width, settings.height);
  validate(scene);
  const Shader shader(scene);
  const PinholeRays rays(scene.camera, settings.width, settings.height);
  const auto shade_rows = [&](const tbb::blocked_range<int>& rows) {
    RowScratch scratch;
    for (int y = rows.begin(); y < rows.end(); ++y) {
      check_interrupt();
      if (settings.batch_shading) {
        shader.shade_row(rays, y, scratch, image);
        continue;
      }
      for (int x = 0; x < settings.width; ++x) image.set(x, y, shader.radiance(rays(x, y)));
    }
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, settings.height), carry_limit(shade_rows));
  return image;
}

}  // namespace specula::render
