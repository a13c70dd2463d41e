#pragma once
// What a frame shows (docs/math.md §5, Figs. 10-11): spheres and triangle meshes, a pinhole camera,
// directional and point lights, and one material whose specular part is any specula Model.
#include <array>
#include <filesystem>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "specula/brdf/vec3.h"
#include "specula/models/model.h"
#include "specula/render/image.h"

namespace specula::render {

struct Ray {
  Vec3 origin;
  Vec3 direction;  ///< unit
};

struct Sphere {
  Vec3 centre;
  double radius = 1;
};

struct Triangle {
  std::array<Vec3, 3> vertices;
  /// Vertex normals for smooth shading (from the OBJ's vn); the face normal when absent.
  std::array<Vec3, 3> normals;
  bool has_normals = false;
};

/// Every face of a Wavefront OBJ file, polygons split into triangle fans (tinyobjloader); only
/// the v, vn, vt and f statements are read: materials (no .mtl is opened), texture coordinates,
/// groups, lines, points and skin weights are ignored. Throws InvalidArgument ("cannot read …")
/// for a missing or unreadable file, an index out of range, or a file with no triangle.
std::vector<Triangle> load_obj(const std::filesystem::path& path);
/// load_obj of an OBJ file's text (an upload's), `name` standing for the path in the messages.
std::vector<Triangle> parse_obj(std::string_view text, std::string_view name);

/// A pinhole camera; the vertical field of view spans the image height.
struct Camera {
  Vec3 position{0, 0, 3.8};
  Vec3 look_at{0, 0, 0};
  Vec3 up{0, 1, 0};
  double vertical_fov_deg = 35;
};

/// A camera on the +z side of a bounding sphere, looking at its centre from the distance where
/// the sphere fills 1/1.15 of the vertical field of view.
Camera framing(const Vec3& centre, double radius, double vertical_fov_deg = 35);
/// framing() of the triangles' bounding box (its centre and half diagonal).
Camera framing(const std::vector<Triangle>& triangles, double vertical_fov_deg = 35);

enum class LightKind { directional, point };

struct Light {
  LightKind kind = LightKind::directional;
  Vec3 direction{-1, 1, 1};  ///< directional lights: toward the light, any length
  Vec3 position{};           ///< point lights
  Rgb colour{1, 1, 1};
  /// Directional: the irradiance E on a surface facing the light is colour·intensity;
  /// point: the radiant intensity, E = colour·intensity / d² at distance d.
  double intensity = 1;
};

/// Throws InvalidArgument "`what`: …" unless the light's direction (directional) or position (point)
/// is finite, a direction non-zero, and its colour and intensity finite and ≥ 0.
void check_light(const Light& light, std::string_view what);
/// The light as "dir:x,y,z:r,g,b:intensity" or "point:x,y,z:r,g,b:intensity", e.g.
/// "dir:-1,1,1:1,1,1:1" (validate's messages, image metadata; the CLI's --light reads it back).
std::string to_string(const Light& light);

/// Lambert diffuse + the model's specular lobe + ambient (docs/math.md §5):
/// L_o = ambient·diffuse + Σ_lights (diffuse/π + specular·f(N, L, V)) · E · max(0, N·L).
struct Material {
  explicit Material(Model specular_model) : model(std::move(specular_model)) {}

  Model model;
  Rgb diffuse{0.55, 0.12, 0.1};  ///< albedo ρ_d per channel
  Rgb specular{0.4, 0.4, 0.4};   ///< ρ_s: scales the model's f per channel
  Rgb ambient{0.03, 0.03, 0.03}; ///< ambient radiance, reflected as ambient·diffuse

  /// The material's BRDF per channel where the model's value is f = f(N, L, V): ρ_d/π + ρ_s·f.
  /// Every CPU renderer shades with it (the GLSL scene shader's scene_surface_radiance as well).
  Rgb brdf(double f) const noexcept { return diffuse * (1 / std::numbers::pi) + specular * f; }
  /// What it reflects of the ambient light: ambient·ρ_d.
  Rgb ambient_radiance() const noexcept { return ambient * diffuse; }
};

/// The most lights a scene may have (each costs one more lobe evaluation per pixel; 4096
/// directional lights make a furnace-like environment).
inline constexpr std::size_t kMaxLights = 4096;

struct Scene {
  Camera camera;
  std::vector<Sphere> spheres;
  std::vector<Triangle> triangles;
  std::vector<Light> lights;
  Material material;
  Rgb background{0, 0, 0};  ///< what a primary ray that hits nothing sees
};

/// One unit sphere at the origin in front of the default camera, one directional light from the
/// upper left front, and `model` as the specular part of the default material.
Scene default_scene(const Model& model);

/// What a caller chooses of a scene, as typed values; make_scene takes the rest from
/// default_scene. The CLI's --scene, --light, --diffuse, … (apps/specula/scene_options.h) and the
/// server's /api/glsl fields both become one of these: no command-line syntax is read here.
struct SceneDescription {
  /// Empty: default_scene's unit sphere and camera; else this mesh alone, seen by framing(mesh).
  std::vector<Triangle> mesh{};
  /// nullopt: default_scene's light; an empty list: no light (e.g. lit by an environment).
  std::optional<std::vector<Light>> lights{};
  /// nullopt: Material's defaults.
  std::optional<Rgb> diffuse{}, specular{}, ambient{};
};

/// default_scene(model) with what `description` chooses. Checks nothing: render_cpu, scene_uniforms
/// and render_environment validate the scene (or call validate).
Scene make_scene(const Model& model, SceneDescription description);

/// Throws InvalidArgument naming the first invalid part: a degenerate camera, a field of view
/// outside (0°, 180°), a sphere radius ≤ 0, a zero light direction, a negative or non-finite
/// colour or intensity, more than kMaxLights lights.
void validate(const Scene& scene);

}  // namespace specula::render
