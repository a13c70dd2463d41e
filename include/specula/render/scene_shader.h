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
#include <string_view>
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

/// One uniform of the scene shader. Each is written once, below: scene_fragment_shader declares
/// and documents them in this order (scene/uniforms.glsl holds no declaration of its own), and
/// gl::Renderer and the server's /api/glsl set and list them by SceneUniforms::visit.
struct SceneUniform {
  const char* name;         ///< "u_resolution"
  std::string_view type;    ///< GLSL: "vec3", "int", … ("sampler2D" is declared highp)
  std::string_view length;  ///< an array's length, a constant of scene/uniforms.glsl; empty: no array
  /// The documentation line: {value} stands for the default scene's value, {max_spheres} and
  /// {max_lights} for kShaderMaxSpheres and kShaderMaxLights.
  std::string_view meaning;
};

namespace scene_uniform {
inline constexpr SceneUniform resolution{"u_resolution", "vec2", "", "whole image, pixels [{value}]"};
inline constexpr SceneUniform pixel_offset{"u_pixel_offset", "vec2", "",
                                           "this tile's lower-left pixel in the image, from the bottom left [{value}]"};
inline constexpr SceneUniform eye{"u_eye", "vec3", "", "camera position [{value}]"};
inline constexpr SceneUniform forward{"u_forward", "vec3", "", "unit view direction [{value}]"};
inline constexpr SceneUniform right{"u_right", "vec3", "", "unit right * tan(fov/2) * width/height [{value}]"};
inline constexpr SceneUniform up{"u_up", "vec3", "", "unit up * tan(fov/2) [{value}]"};
inline constexpr SceneUniform sphere_count{"u_sphere_count", "int", "", "spheres used, <= {max_spheres} [{value}]"};
inline constexpr SceneUniform spheres{"u_spheres", "vec4", "SCENE_MAX_SPHERES", "centre, radius [{value}]"};
inline constexpr SceneUniform light_count{"u_light_count", "int", "", "lights used, <= {max_lights} [{value}]"};
inline constexpr SceneUniform lights{"u_lights", "vec4", "SCENE_MAX_LIGHTS",
                                     "w 0: unit direction toward the light; w 1: position [{value}]"};
inline constexpr SceneUniform light_irradiance{"u_light_irradiance", "vec3", "SCENE_MAX_LIGHTS",
                                               "colour * intensity, E; points: / d^2 [{value}]"};
inline constexpr SceneUniform diffuse{"u_diffuse", "vec3", "", "rho_d, Lambert albedo [{value}]"};
inline constexpr SceneUniform specular{"u_specular", "vec3", "", "rho_s, scales specula_brdf [{value}]"};
inline constexpr SceneUniform ambient{"u_ambient", "vec3", "", "ambient radiance, reflected as ambient * rho_d [{value}]"};
inline constexpr SceneUniform background{"u_background", "vec3", "", "radiance where a ray hits nothing [{value}]"};
inline constexpr SceneUniform model_params{"u_model_params", "vec4", "", "specula_brdf's params [{value}]"};
inline constexpr SceneUniform triangle_count{"u_triangle_count", "int", "", "triangles in u_triangles, 0 = no mesh [{value}]"};
inline constexpr SceneUniform triangles{"u_triangles", "sampler2D", "",
                                        "RGBA32F, 6 texels a triangle: v0 (w: has normals), e1, e2, n0, n1, n2"};
inline constexpr SceneUniform bvh{"u_bvh", "sampler2D", "",
                                  "RGBA32F, 2 texels a node: (min, first), (max, count); count 0: inner"};
inline constexpr SceneUniform display{"u_display", "int", "",
                                      "0: linear radiance out; 1: exposure, tone map, sRGB [1 for a viewer]"};
inline constexpr SceneUniform exposure{"u_exposure", "float", "", "stops, with u_display 1 [{value}]"};
inline constexpr SceneUniform tone_map{"u_tone_map", "int", "", "0 none (clamp), 1 ACES (Narkowicz), with u_display 1 [{value}]"};

/// Every uniform, in the shader's order.
inline constexpr std::array all{resolution, pixel_offset, eye, forward, right, up, sphere_count, spheres,
                                light_count, lights, light_irradiance, diffuse, specular, ambient, background,
                                model_params, triangle_count, triangles, bvh, display, exposure, tone_map};
}  // namespace scene_uniform

/// Every uniform of the scene shader but the samplers (bound with their textures), as the shader
/// reads it (float, camera vectors pre-scaled).
struct SceneUniforms {
  std::array<float, 2> resolution{};      ///< u_resolution: the whole image, pixels
  /// u_pixel_offset: the first tile's, 0, 0 (gl::draw_full_screen sets each tile's).
  std::array<float, 2> pixel_offset{};
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

  /// f(uniform, value) for each of the above in the shader's order (scene_uniform::all without
  /// the samplers); u_sphere_count and u_light_count, the sizes of spheres and lights, as int.
  template <class F>
  void visit(F&& f) const {
    namespace u = scene_uniform;
    f(u::resolution, resolution);
    f(u::pixel_offset, pixel_offset);
    f(u::eye, eye);
    f(u::forward, forward);
    f(u::right, right);
    f(u::up, up);
    f(u::sphere_count, static_cast<int>(spheres.size()));
    f(u::spheres, spheres);
    f(u::light_count, static_cast<int>(lights.size()));
    f(u::lights, lights);
    f(u::light_irradiance, light_irradiance);
    f(u::diffuse, diffuse);
    f(u::specular, specular);
    f(u::ambient, ambient);
    f(u::background, background);
    f(u::model_params, model_params);
    f(u::triangle_count, triangle_count);
    f(u::display, display);
    f(u::exposure, exposure);
    f(u::tone_map, tone_map);
  }
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
