#pragma once
// What the CPU renderers share (render.cpp: local lights; environment_render.cpp: environment
// lighting): the primary rays of the pinhole camera, and the scene's spheres and triangles with
// their nearest hit and shadow rays.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "specula/brdf/directions.h"
#include "specula/render/bvh.h"
#include "specula/render/scene.h"

namespace specula::render::detail {

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// The stable ray/sphere intersection of Haines et al. 2019 ("Precision Improvements for
/// Ray/Sphere Intersection", Ray Tracing Gems, ch. 7): the discriminant from |f − (f·d)d|² and
/// the second root from the product of the roots. The nearest t in (t_min, t_max), if any.
inline std::optional<double> intersect(const Ray& ray, const Sphere& sphere, double t_min, double t_max) noexcept {
  const Vec3 f = ray.origin - sphere.centre;
  const double b = -dot(f, ray.direction);
  const Vec3 chord = f + ray.direction * b;
  const double r2 = sphere.radius * sphere.radius;
  const double discriminant = r2 - dot(chord, chord);
  if (discriminant < 0) return std::nullopt;
  const double q = b + std::copysign(std::sqrt(discriminant), b);
  const double t0 = (dot(f, f) - r2) / q, t1 = q;
  const double near = std::min(t0, t1), far = std::max(t0, t1);
  if (near > t_min && near < t_max) return near;
  if (far > t_min && far < t_max) return far;
  return std::nullopt;
}

struct SurfaceHit {
  Vec3 point;
  Vec3 normal;     ///< shading normal, unit, on the viewer's side
  Vec3 geometric;  ///< face normal, unit, on the viewer's side
};

// Spheres tested one by one, triangles through the BVH.
class Geometry {
 public:
  explicit Geometry(const Scene& scene) : spheres_(scene.spheres), bvh_(scene.triangles) {}

  std::optional<SurfaceHit> closest(const Ray& ray) const noexcept {
    double t_max = kInfinity;
    const Sphere* nearest_sphere = nullptr;
    for (const Sphere& s : spheres_)
      if (const auto t = intersect(ray, s, 0, t_max)) {
        t_max = *t;
        nearest_sphere = &s;
      }
    if (const auto hit = bvh_.closest(ray, 0, t_max)) return triangle_surface(ray, *hit);
    if (nearest_sphere) return sphere_surface(ray, *nearest_sphere, t_max);
    return std::nullopt;
  }

  /// A lone sphere is convex: nothing in the scene can shadow it beyond N·L ≤ 0.
  bool casts_shadows() const noexcept { return bvh_.size() > 0 || spheres_.size() > 1; }

  /// Whether the unit direction `l` from the hit is blocked before `distance`. The shadow ray
  /// leaves from just above the face, on the viewer's side; a direction behind the face
  /// (possible with smooth normals) is blocked by the face itself.
  bool blocked(const SurfaceHit& hit, const Vec3& l, double distance) const noexcept {
    if (dot(hit.geometric, l) <= 0) return true;
    const double scale = std::max({1.0, std::abs(hit.point.x), std::abs(hit.point.y), std::abs(hit.point.z)});
    const double offset = 1e-9 * scale;
    return occluded({hit.point + hit.geometric * offset, l}, distance - offset);
  }

 private:
  bool occluded(const Ray& ray, double t_max) const noexcept {
    for (const Sphere& s : spheres_)
      if (intersect(ray, s, 0, t_max)) return true;
    return bvh_.occluded(ray, 0, t_max);
  }

  static SurfaceHit facing_viewer(const Ray& ray, double t, Vec3 normal, Vec3 geometric) noexcept {
    if (dot(geometric, ray.direction) > 0) geometric = -geometric;
    if (dot(normal, geometric) < 0) normal = -normal;
    return {ray.origin + ray.direction * t, normal, geometric};
  }

  static SurfaceHit sphere_surface(const Ray& ray, const Sphere& s, double t) noexcept {
    const Vec3 n = (ray.origin + ray.direction * t - s.centre) * (1 / s.radius);
    return facing_viewer(ray, t, n, n);
  }

  static SurfaceHit triangle_surface(const Ray& ray, const TriangleHit& hit) noexcept {
    const Triangle& tri = *hit.triangle;
    const Vec3 face = normalized(cross(tri.vertices[1] - tri.vertices[0], tri.vertices[2] - tri.vertices[0]));
    const Vec3 smooth = tri.normals[0] * (1 - hit.u - hit.v) + tri.normals[1] * hit.u + tri.normals[2] * hit.v;
    const bool use_smooth = tri.has_normals && length(smooth) > 0;
    return facing_viewer(ray, hit.t, use_smooth ? normalized(smooth) : face, face);
  }

  std::vector<Sphere> spheres_;
  Bvh bvh_;
};

// Primary rays through pixel centres: x right, row 0 at the top.
class PinholeRays {
 public:
  PinholeRays(const Camera& camera, int width, int height)
      : origin_(camera.position), width_(width), height_(height) {
    forward_ = normalized(camera.look_at - camera.position);
    right_ = normalized(cross(forward_, camera.up));
    up_ = cross(right_, forward_);
    const double tan_half = std::tan(radians(camera.vertical_fov_deg) / 2);
    up_ = up_ * tan_half;
    right_ = right_ * (tan_half * width / height);
  }

  Ray operator()(int x, int y) const noexcept {
    const double sx = 2 * (x + 0.5) / width_ - 1, sy = 1 - 2 * (y + 0.5) / height_;
    return {origin_, normalized(forward_ + right_ * sx + up_ * sy)};
  }

 private:
  Vec3 origin_, forward_, right_, up_;
  int width_, height_;
};

}  // namespace specula::render::detail
