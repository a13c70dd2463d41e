#pragma once
// The GLSL scene shader: what render_cpu computes per pixel (include/specula/render/render.h),
// as a full-screen fragment shader. One primary ray through the pixel centre, spheres and a
// triangle mesh (its BVH in float textures), directional and point lights, shadow rays where the
// CPU casts them, docs/math.md §5's local shading with any model's specula_brdf (glsl/glsl.h), and
// optionally the display transform of render/image.h. No GL dependency: the strings and the
// values of the uniforms and textures are made here; specula_gl (gl/render_gl.h) runs them.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "specula/glsl/glsl.h"
#include "specula/render/bvh.h"
#include "specula/render/image.h"
#include "specula/render/render.h"
#include "specula/render/scene.h"

namespace specula::render {

/// The shader's fixed limits (uniform array sizes and the BVH traversal stack).
inline constexpr int kShaderMaxSpheres = 16;
inline constexpr int kShaderMaxLights = 8;
inline constexpr int kShaderBvhStackSize = 32;
/// Triangle and node indices travel as float texels: exact below 2^24.
inline constexpr std::size_t kShaderMaxMeshElements = std::size_t{1} << 24;

/// A triangle covering the viewport, its corners from gl_VertexID (draw 3 vertices, no attributes).
std::string scene_vertex_shader(glsl::Dialect dialect);

/// What the fragment shader traces. Both shaders render any scene of spheres; only the second
/// traverses u_bvh. On llvmpipe the traversal costs ~4x per pixel even where u_triangle_count = 0
/// (a branch not taken still runs with its SIMD lanes masked off), hence the choice.
enum class SceneGeometry { spheres, spheres_and_mesh };

/// spheres for a scene without triangles, else spheres_and_mesh.
SceneGeometry geometry_of(const Scene& scene) noexcept;

/// version_header + documentation of the uniforms (with the default scene's values) + uniforms +
/// glsl::model_glsl(model) + geometry + shading + display + main. Writes linear radiance, or, with
/// u_display = 1, the display value of render/image.h (exposure, tone map, sRGB) in [0, 1].
/// The geometry is the line `#define SCENE_MESH 0|1` (guarded by #ifndef), which a viewer may edit.
std::string scene_fragment_shader(const Model& model, glsl::Dialect dialect,
                                  SceneGeometry geometry = SceneGeometry::spheres_and_mesh);

/// Every uniform of the scene shader but the samplers and u_pixel_offset (set per tile), as the
/// shader reads it (float, camera vectors pre-scaled).
struct SceneUniforms {
  std::array<float, 2> resolution{};      ///< u_resolution: the whole image, pixels
  std::array<float, 3> eye{};             ///< u_eye: camera position
  std::array<float, 3> forward{};         ///< u_forward: unit view direction
  std::array<float, 3> right{};           ///< u_right: unit right · tan(fov/2) · width/height
  std::array<float, 3> up{};              ///< u_up: unit up · tan(fov/2)
  std::vector<std::array<float, 4>> spheres;           ///< u_spheres: centre, radius
  std::vector<std::array<float, 4>> lights;            ///< u_lights: unit direction toward (w = 0) or position (w = 1)
  std::vector<std::array<float, 3>> light_irradiance;  ///< u_light_irradiance: colour · intensity
  std::array<float, 3> diffuse{}, specular{}, ambient{}, background{};  ///< u_diffuse, …
  std::array<float, 4> model_params{};    ///< u_model_params: glsl::model_params(model)
  int triangle_count = 0;                 ///< u_triangle_count: 0 = no mesh
  int display = 0;                        ///< u_display: 0 linear radiance, 1 display values
  float exposure = 0;                     ///< u_exposure: stops (u_display = 1)
  int tone_map = 0;                       ///< u_tone_map: 0 none, 1 aces (u_display = 1)
};

/// The uniforms for `scene` at `settings`' size, with `display` applied in the shader if given.
/// Throws InvalidArgument for an invalid scene or size (as render_cpu) and for more than
/// kShaderMaxSpheres spheres, kShaderMaxLights lights or kShaderMaxMeshElements triangles.
SceneUniforms scene_uniforms(const Scene& scene, const RenderSettings& settings,
                             const std::optional<Display>& display = std::nullopt);

/// A mesh as the shader reads it: two RGBA32F textures `width` texels wide, row-major, the last
/// row padded with zeros. u_triangles: 6 texels per triangle in BVH leaf order — v0 (w: 1 if it
/// has vertex normals), e1 = v1 − v0, e2 = v2 − v0, n0, n1, n2 (edges from the double vertices).
/// u_bvh: 2 texels per node — (box min, first), (box max, count), boxes rounded outward to float.
struct MeshTextures {
  int width = 0;
  int triangle_rows = 0;
  int node_rows = 0;
  std::vector<float> triangles;  ///< 4 floats a texel
  std::vector<float> nodes;
};

/// Throws InvalidArgument for a BVH deeper than the shader's stack or more than kShaderMaxMeshElements
/// triangles or nodes, or a width < 1.
MeshTextures mesh_textures(const Bvh& bvh, int width);

}  // namespace specula::render
