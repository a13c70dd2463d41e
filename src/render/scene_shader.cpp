#include "specula/render/scene_shader.h"

#include <cmath>
#include <fmt/format.h>
#include <limits>

#include "specula/brdf/directions.h"
#include "specula/exceptions.h"

namespace specula::render {
namespace {

// --- GLSL text (ASCII only: some GLSL front ends reject other bytes even in comments) ---

constexpr const char* kVertexBody = R"(
// A triangle covering the viewport from gl_VertexID alone: corners (-1,-1), (3,-1), (-1,3).
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kUniforms = R"(
// SCENE_MESH 0 leaves the triangle traversal out: for scenes of spheres alone. (llvmpipe runs
// code under a branch not taken with its lanes masked off: the unused traversal would cost it 4x.)
#ifndef SCENE_MESH
#define SCENE_MESH {mesh}
#endif
const int SCENE_MAX_SPHERES = {max_spheres};
const int SCENE_MAX_LIGHTS = {max_lights};
const int SCENE_BVH_STACK = {stack};
const float SCENE_FAR = 3.0e38;
const float SCENE_INV_PI = 0.318309886;

uniform vec2 u_resolution;
uniform vec2 u_pixel_offset;
uniform vec3 u_eye;
uniform vec3 u_forward;
uniform vec3 u_right;
uniform vec3 u_up;
uniform int u_sphere_count;
uniform vec4 u_spheres[SCENE_MAX_SPHERES];
uniform int u_light_count;
uniform vec4 u_lights[SCENE_MAX_LIGHTS];
uniform vec3 u_light_irradiance[SCENE_MAX_LIGHTS];
uniform vec3 u_diffuse;
uniform vec3 u_specular;
uniform vec3 u_ambient;
uniform vec3 u_background;
uniform vec4 u_model_params;
uniform int u_triangle_count;
uniform highp sampler2D u_triangles;
uniform highp sampler2D u_bvh;
uniform int u_display;
uniform float u_exposure;
uniform int u_tone_map;

out vec4 scene_colour;
)";

constexpr const char* kGeometry = R"(
// Haines et al. 2019, "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, ch. 7): discriminant from |f - (f.d)d|^2, far root from the product of the roots. Nearest t in (t_min, t_max), or -1.
float scene_sphere_hit(vec3 origin, vec3 direction, vec4 sphere, float t_min, float t_max) {
  vec3 f = origin - sphere.xyz;
  float b = -dot(f, direction);
  vec3 chord = f + b * direction;
  float r2 = sphere.w * sphere.w;
  float discriminant = r2 - dot(chord, chord);
  if (discriminant < 0.0) return -1.0;
  float q = b + (b < 0.0 ? -1.0 : 1.0) * sqrt(discriminant);
  float t0 = (dot(f, f) - r2) / q;
  float near_t = min(t0, q), far_t = max(t0, q);
  if (near_t > t_min && near_t < t_max) return near_t;
  if (far_t > t_min && far_t < t_max) return far_t;
  return -1.0;
}

// The i-th RGBA32F texel of a texture read as a flat array, row-major.
vec4 scene_texel(highp sampler2D data, int i) {
  int width = textureSize(data, 0).x;
  return texelFetch(data, ivec2(i % width, i / width), 0);
}

// Moller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection" (render/bvh.cpp): (t, u, v) of a hit with t_min < t < t_max, both faces; t = -1 if none.
vec3 scene_triangle_hit(vec3 origin, vec3 direction, int triangle, float t_min, float t_max) {
  vec3 v0 = scene_texel(u_triangles, 6 * triangle).xyz;
  vec3 e1 = scene_texel(u_triangles, 6 * triangle + 1).xyz;
  vec3 e2 = scene_texel(u_triangles, 6 * triangle + 2).xyz;
  vec3 p = cross(direction, e2);
  float det = dot(e1, p);
  if (det == 0.0) return vec3(-1.0);
  float inv_det = 1.0 / det;
  vec3 s = origin - v0;
  float u = dot(s, p) * inv_det;
  if (!(u >= 0.0 && u <= 1.0)) return vec3(-1.0);
  vec3 q = cross(s, e1);
  float v = dot(direction, q) * inv_det;
  if (!(v >= 0.0 && u + v <= 1.0)) return vec3(-1.0);
  float t = dot(e2, q) * inv_det;
  return t > t_min && t < t_max ? vec3(t, u, v) : vec3(-1.0);
}

// Kay & Kajiya 1986 slab test (render/bvh.cpp); the exit distance widened by 1 + 2 gamma_3 as in Pharr, Jakob & Humphreys, PBR 3rd ed., 3.9.2, so float rounding never drops a box the double test keeps. Entry t within (t_min, t_max), or SCENE_FAR.
float scene_box_entry(int node, vec3 origin, vec3 inverse, float t_min, float t_max) {
  vec3 lo = scene_texel(u_bvh, 2 * node).xyz;
  vec3 hi = scene_texel(u_bvh, 2 * node + 1).xyz;
  vec3 a = (lo - origin) * inverse, b = (hi - origin) * inverse;
  vec3 near_t = min(a, b), far_t = max(a, b) * 1.0000004;
  float enter = max(t_min, max(near_t.x, max(near_t.y, near_t.z)));
  float leave = min(t_max, min(far_t.x, min(far_t.y, far_t.z)));
  return enter <= leave ? enter : SCENE_FAR;
}

// 1/d per axis, a zero component replaced by a tiny one of the same sign so that no slab gives 0 * inf = NaN (render/bvh.cpp lets a NaN slab constrain nothing; this keeps the same boxes).
vec3 scene_inverse_direction(vec3 d) {
  vec3 tiny = mix(vec3(1e-30), vec3(-1e-30), lessThan(d, vec3(0.0)));
  return 1.0 / mix(d, tiny, lessThan(abs(d), vec3(1e-30)));
}

// render/bvh.cpp's traversal: a stack of (node, entry t), nearer child popped first. Returns the nearest hit (t, u, v) with t_min < t < t_max (any hit if any_hit) and its triangle, or t = -1.
vec3 scene_mesh_hit(vec3 origin, vec3 direction, float t_min, float t_max, bool any_hit, out int triangle) {
  triangle = -1;
  vec3 best = vec3(-1.0);
  if (u_triangle_count == 0) return best;
  vec3 inverse = scene_inverse_direction(direction);
  int nodes[SCENE_BVH_STACK];
  float entries[SCENE_BVH_STACK];
  int top = 1;
  nodes[0] = 0;
  entries[0] = scene_box_entry(0, origin, inverse, t_min, t_max);
  while (top > 0) {
    --top;
    int node = nodes[top];
    if (!(entries[top] < t_max)) continue;
    vec4 lo = scene_texel(u_bvh, 2 * node), hi = scene_texel(u_bvh, 2 * node + 1);
    int count = int(hi.w);
    if (count > 0) {
      for (int i = int(lo.w); i < int(lo.w) + count; ++i) {
        vec3 hit = scene_triangle_hit(origin, direction, i, t_min, t_max);
        if (hit.x < 0.0) continue;
        t_max = hit.x;
        best = hit;
        triangle = i;
        if (any_hit) return best;
      }
      continue;
    }
    int near_node = node + 1, far_node = int(lo.w);
    float near_t = scene_box_entry(near_node, origin, inverse, t_min, t_max);
    float far_t = scene_box_entry(far_node, origin, inverse, t_min, t_max);
    if (far_t < near_t) {
      int n = near_node; near_node = far_node; far_node = n;
      float t = near_t; near_t = far_t; far_t = t;
    }
    nodes[top] = far_node; entries[top] = far_t; ++top;
    nodes[top] = near_node; entries[top] = near_t; ++top;
  }
  return best;
}

struct SceneSurface {
  vec3 point;
  vec3 normal;     // shading normal, unit, on the viewer's side
  vec3 geometric;  // face normal, unit, on the viewer's side
};

// render.cpp, Geometry::facing_viewer: surfaces are two-sided, both normals turned toward the viewer.
SceneSurface scene_facing_viewer(vec3 point, vec3 direction, vec3 normal, vec3 geometric) {
  if (dot(geometric, direction) > 0.0) geometric = -geometric;
  if (dot(normal, geometric) < 0.0) normal = -normal;
  return SceneSurface(point, normal, geometric);
}

// render.cpp, Geometry::triangle_surface: the face normal, or the vertex normals interpolated at (u, v) where the triangle has them.
SceneSurface scene_triangle_surface(vec3 origin, vec3 direction, int triangle, vec3 hit) {
  vec4 v0 = scene_texel(u_triangles, 6 * triangle);
  vec3 face = normalize(cross(scene_texel(u_triangles, 6 * triangle + 1).xyz, scene_texel(u_triangles, 6 * triangle + 2).xyz));
  vec3 smooth_normal = scene_texel(u_triangles, 6 * triangle + 3).xyz * (1.0 - hit.y - hit.z) +
                       scene_texel(u_triangles, 6 * triangle + 4).xyz * hit.y +
                       scene_texel(u_triangles, 6 * triangle + 5).xyz * hit.z;
  bool use_smooth = v0.w > 0.5 && length(smooth_normal) > 0.0;
  return scene_facing_viewer(origin + direction * hit.x, direction, use_smooth ? normalize(smooth_normal) : face, face);
}

// render.cpp, Geometry::closest: the nearest sphere, then the mesh closer than it. False if the ray hits nothing.
bool scene_closest(vec3 origin, vec3 direction, out SceneSurface surface) {
  float t_max = SCENE_FAR;
  int sphere = -1;
  for (int i = 0; i < u_sphere_count; ++i) {
    float t = scene_sphere_hit(origin, direction, u_spheres[i], 0.0, t_max);
    if (t < 0.0) continue;
    t_max = t;
    sphere = i;
  }
#if SCENE_MESH
  int triangle;
  vec3 hit = scene_mesh_hit(origin, direction, 0.0, t_max, false, triangle);
  if (triangle >= 0) {
    surface = scene_triangle_surface(origin, direction, triangle, hit);
    return true;
  }
#endif
  if (sphere < 0) return false;
  vec3 point = origin + direction * t_max;
  vec3 n = (point - u_spheres[sphere].xyz) / u_spheres[sphere].w;
  surface = scene_facing_viewer(point, direction, n, n);
  return true;
}

// render.cpp, Geometry::occluded: any sphere or triangle with 0 < t < t_max.
bool scene_occluded(vec3 origin, vec3 direction, float t_max) {
  for (int i = 0; i < u_sphere_count; ++i)
    if (scene_sphere_hit(origin, direction, u_spheres[i], 0.0, t_max) >= 0.0) return true;
#if SCENE_MESH
  int triangle;
  scene_mesh_hit(origin, direction, 0.0, t_max, true, triangle);
  return triangle >= 0;
#else
  return false;
#endif
}

// Wachter & Binder 2019, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing Gems, ch. 6): p moved off its surface along n by a few float ulps (a fixed distance near the origin). The CPU's 1e-9 |p| offset is below float resolution.
vec3 scene_offset_ray(vec3 p, vec3 n) {
  ivec3 ulps = ivec3(256.0 * n) * (ivec3(1) - 2 * ivec3(lessThan(p, vec3(0.0))));
  vec3 moved = intBitsToFloat(floatBitsToInt(p) + ulps);
  return mix(moved, p + n / 65536.0, lessThan(abs(p), vec3(1.0 / 32.0)));
}
)";

constexpr const char* kShading = R"(
// render.cpp, Shader::in_shadow: a light below the face is blocked by the face itself; else a shadow ray from just above the face toward the light.
bool scene_in_shadow(SceneSurface s, vec3 L, float distance) {
  if (dot(s.geometric, L) <= 0.0) return true;
  vec3 origin = scene_offset_ray(s.point, s.geometric);
  return scene_occluded(origin, L, distance - length(origin - s.point));
}

// docs/math.md 5 (the paper's local illumination, render.cpp Shader::surface_radiance): L_o = ambient rho_d + sum over lights of (rho_d/pi + rho_s f(N, L, V)) E max(0, N.L), lights at N.L <= 0 or in shadow dropped. Shadow rays only where the CPU casts them: more than one sphere, or a mesh.
vec3 scene_surface_radiance(SceneSurface s, vec3 V) {
  vec3 sum = u_ambient * u_diffuse;
  bool shadows = u_triangle_count > 0 || u_sphere_count > 1;
  for (int i = 0; i < u_light_count; ++i) {
    vec3 L = u_lights[i].xyz;
    vec3 E = u_light_irradiance[i];
    float distance = SCENE_FAR;
    if (u_lights[i].w > 0.5) {  // point light: E = colour intensity / d^2
      vec3 to_light = u_lights[i].xyz - s.point;
      float d2 = dot(to_light, to_light);
      distance = sqrt(d2);
      L = to_light / distance;
      E = E / d2;
    }
    float cos_i = dot(s.normal, L);
    if (cos_i <= 0.0 || (shadows && scene_in_shadow(s, L, distance))) continue;
    sum += (u_diffuse * SCENE_INV_PI + u_specular * specula_brdf(s.normal, L, V, u_model_params)) * E * cos_i;
  }
  return sum;
}
)";

constexpr const char* kDisplay = R"(
// Narkowicz 2016, "ACES Filmic Tone Mapping Curve" (render/image.h aces_narkowicz): x(2.51x + 0.03)/(x(2.43x + 0.59) + 0.14), clamped to [0, 1].
vec3 scene_aces(vec3 x) {
  return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// IEC 61966-2-1, the sRGB transfer curve (render/image.h srgb_encode): 12.92 L for L <= 0.0031308, else 1.055 L^(1/2.4) - 0.055.
vec3 scene_srgb_encode(vec3 l) {
  return mix(1.055 * pow(l, vec3(1.0 / 2.4)) - 0.055, 12.92 * l, lessThanEqual(l, vec3(0.0031308)));
}

// render/image.h Display and to_srgb8 before the rounding: radiance 2^exposure, tone-mapped (u_tone_map 1: ACES), clamped to [0, 1], sRGB-encoded.
vec3 scene_display(vec3 radiance) {
  vec3 x = radiance * exp2(u_exposure);
  if (u_tone_map == 1) x = scene_aces(x);
  return scene_srgb_encode(clamp(x, 0.0, 1.0));
}
)";

constexpr const char* kMain = R"(
// render.cpp PinholeRays: the ray through the pixel centre; gl_FragCoord counts rows from the bottom, so sy = 2 y/h - 1 is the CPU's 1 - 2(row + 0.5)/h once the image is flipped.
void main() {
  vec2 s = 2.0 * (gl_FragCoord.xy + u_pixel_offset) / u_resolution - 1.0;
  vec3 direction = normalize(u_forward + u_right * s.x + u_up * s.y);
  SceneSurface surface;
  vec3 radiance = scene_closest(u_eye, direction, surface) ? scene_surface_radiance(surface, -direction) : u_background;
  scene_colour = vec4(u_display == 1 ? scene_display(radiance) : radiance, 1.0);
}
)";

// --- The uniforms' documentation, with the default scene's values ---

std::string numbers(const float* values, std::size_t count) {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) text += (i ? ", " : "") + fmt::format("{:.6g}", values[i]);
  return text;
}

template <std::size_t N>
std::string numbers(const std::array<float, N>& values) {
  return numbers(values.data(), N);
}

std::string uniform_documentation(const Model& model) {
  const RenderSettings size{512, 512};
  const SceneUniforms d = scene_uniforms(default_scene(model), size);
  std::string text = fmt::format(
      "// specula scene shader: the CPU renderer's pixel (render/render.h, docs/math.md 5) with model '{}'.\n"
      "// Draw 3 vertices of scene_vertex_shader over the image (or tiles of it) and set every uniform;\n"
      "// specula's render::scene_uniforms and render::mesh_textures compute them from a scene.\n"
      "// The default scene's values at 512x512 are in brackets: a unit sphere lit from the upper left front.\n",
      model.id());
  const std::vector<std::pair<std::string, std::string>> rows{
      {"vec2 u_resolution", fmt::format("whole image, pixels [{}]", numbers(d.resolution))},
      {"vec2 u_pixel_offset", "this tile's lower-left pixel in the image, from the bottom left [0, 0]"},
      {"vec3 u_eye", fmt::format("camera position [{}]", numbers(d.eye))},
      {"vec3 u_forward", fmt::format("unit view direction [{}]", numbers(d.forward))},
      {"vec3 u_right", fmt::format("unit right * tan(fov/2) * width/height [{}]", numbers(d.right))},
      {"vec3 u_up", fmt::format("unit up * tan(fov/2) [{}]", numbers(d.up))},
      {"int u_sphere_count", fmt::format("spheres used, <= {} [{}]", kShaderMaxSpheres, d.spheres.size())},
      {"vec4 u_spheres[]", fmt::format("centre, radius [{}]", numbers(d.spheres[0]))},
      {"int u_light_count", fmt::format("lights used, <= {} [{}]", kShaderMaxLights, d.lights.size())},
      {"vec4 u_lights[]", fmt::format("w 0: unit direction toward the light; w 1: position [{}]", numbers(d.lights[0]))},
      {"vec3 u_light_irradiance[]", fmt::format("colour * intensity, E; points: / d^2 [{}]", numbers(d.light_irradiance[0]))},
      {"vec3 u_diffuse", fmt::format("rho_d, Lambert albedo [{}]", numbers(d.diffuse))},
      {"vec3 u_specular", fmt::format("rho_s, scales specula_brdf [{}]", numbers(d.specular))},
      {"vec3 u_ambient", fmt::format("ambient radiance, reflected as ambient * rho_d [{}]", numbers(d.ambient))},
      {"vec3 u_background", fmt::format("radiance where a ray hits nothing [{}]", numbers(d.background))},
      {"vec4 u_model_params", fmt::format("specula_brdf's params [{}]", numbers(d.model_params))},
      {"int u_triangle_count", "triangles in u_triangles, 0 = no mesh [0]"},
      {"sampler2D u_triangles", "RGBA32F, 6 texels a triangle: v0 (w: has normals), e1, e2, n0, n1, n2"},
      {"sampler2D u_bvh", "RGBA32F, 2 texels a node: (min, first), (max, count); count 0: inner"},
      {"int u_display", "0: linear radiance out; 1: exposure, tone map, sRGB [1 for a viewer]"},
      {"float u_exposure", "stops, with u_display 1 [0]"},
      {"int u_tone_map", "0 none (clamp), 1 ACES (Narkowicz), with u_display 1 [0]"}};
  for (const auto& [name, meaning] : rows) text += fmt::format("//   {:<26} {}\n", name, meaning);
  return text;
}

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

// --- Values ---

std::array<float, 3> to_float(const Vec3& v) {
  return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
}

std::array<float, 3> to_float(const Rgb& c) {
  return {static_cast<float>(c.r), static_cast<float>(c.g), static_cast<float>(c.b)};
}

// The float nearest to x on the side of `toward` (boxes rounded outward).
float rounded_toward(double x, float toward) {
  const auto f = static_cast<float>(x);
  if (toward < 0 ? static_cast<double>(f) <= x : static_cast<double>(f) >= x) return f;
  return std::nextafter(f, toward);
}

void put_texel(std::vector<float>& data, const std::array<float, 3>& xyz, float w) {
  data.insert(data.end(), {xyz[0], xyz[1], xyz[2], w});
}

// Pads `data` (texels of 4 floats) to whole rows of `width` texels; returns the row count.
int pad_rows(std::vector<float>& data, int width) {
  const std::size_t texels = data.size() / 4, row = static_cast<std::size_t>(width);
  const std::size_t rows = std::max<std::size_t>(1, (texels + row - 1) / row);
  data.resize(4 * rows * row, 0.0f);
  return static_cast<int>(rows);
}

// The Image's size limits (render_cpu's), without allocating the image.
void check_size(const RenderSettings& s) {
  if (s.width < 1 || s.height < 1 || s.width > kMaxImageSide || s.height > kMaxImageSide)
    throw InvalidArgument(fmt::format("image size {}x{} is invalid: width and height must be in [1, {}]", s.width,
                                      s.height, kMaxImageSide));
}

void set_camera(SceneUniforms& u, const Camera& camera, const RenderSettings& settings) {
  // PinholeRays (render.cpp), in double, then rounded.
  const Vec3 forward = normalized(camera.look_at - camera.position);
  const Vec3 right = normalized(cross(forward, camera.up));
  const Vec3 up = cross(right, forward);
  const double tan_half = std::tan(radians(camera.vertical_fov_deg) / 2);
  u.eye = to_float(camera.position);
  u.forward = to_float(forward);
  u.right = to_float(right * (tan_half * settings.width / settings.height));
  u.up = to_float(up * tan_half);
}

void set_lights(SceneUniforms& u, const std::vector<Light>& lights) {
  for (const Light& light : lights) {
    const bool directional = light.kind == LightKind::directional;
    const auto xyz = to_float(directional ? normalized(light.direction) : light.position);
    u.lights.push_back({xyz[0], xyz[1], xyz[2], directional ? 0.0f : 1.0f});
    u.light_irradiance.push_back(to_float(light.colour * light.intensity));
  }
}

}  // namespace

SceneGeometry geometry_of(const Scene& scene) noexcept {
  return scene.triangles.empty() ? SceneGeometry::spheres : SceneGeometry::spheres_and_mesh;
}

std::string scene_vertex_shader(glsl::Dialect dialect) {
  return glsl::version_header(dialect) + kVertexBody;
}

std::string scene_fragment_shader(const Model& model, glsl::Dialect dialect, SceneGeometry geometry) {
  std::string uniforms = replace_all(kUniforms, "{mesh}", geometry == SceneGeometry::spheres ? "0" : "1");
  uniforms = replace_all(uniforms, "{max_spheres}", std::to_string(kShaderMaxSpheres));
  uniforms = replace_all(uniforms, "{max_lights}", std::to_string(kShaderMaxLights));
  uniforms = replace_all(uniforms, "{stack}", std::to_string(kShaderBvhStackSize));
  return glsl::version_header(dialect) + uniform_documentation(model) + uniforms + "\n" + glsl::model_glsl(model) +
         kGeometry + kShading + kDisplay + kMain;
}

SceneUniforms scene_uniforms(const Scene& scene, const RenderSettings& settings,
                             const std::optional<Display>& display) {
  check_size(settings);
  validate(scene);
  if (scene.triangles.size() >= kShaderMaxMeshElements)
    throw InvalidArgument(fmt::format("the GL renderer takes fewer than {} triangles; the scene has {}",
                                      kShaderMaxMeshElements, scene.triangles.size()));
  if (scene.spheres.size() > static_cast<std::size_t>(kShaderMaxSpheres))
    throw InvalidArgument(fmt::format("the GL renderer draws at most {} spheres; the scene has {}", kShaderMaxSpheres,
                                      scene.spheres.size()));
  if (scene.lights.size() > static_cast<std::size_t>(kShaderMaxLights))
    throw InvalidArgument(fmt::format("the GL renderer takes at most {} lights; the scene has {}", kShaderMaxLights,
                                      scene.lights.size()));
  SceneUniforms u;
  u.resolution = {static_cast<float>(settings.width), static_cast<float>(settings.height)};
  set_camera(u, scene.camera, settings);
  for (const Sphere& s : scene.spheres) {
    const auto c = to_float(s.centre);
    u.spheres.push_back({c[0], c[1], c[2], static_cast<float>(s.radius)});
  }
  set_lights(u, scene.lights);
  const Material& m = scene.material;
  u.diffuse = to_float(m.diffuse);
  u.specular = to_float(m.specular);
  u.ambient = to_float(m.ambient);
  u.background = to_float(scene.background);
  u.model_params = glsl::model_params(m.model);
  u.triangle_count = static_cast<int>(scene.triangles.size());
  if (display) {
    u.display = 1;
    u.exposure = static_cast<float>(display->exposure);
    u.tone_map = display->tone_map == ToneMap::aces ? 1 : 0;
  }
  return u;
}

MeshTextures mesh_textures(const Bvh& bvh, int width) {
  if (width < 1) throw InvalidArgument(fmt::format("texture width {} is invalid: it must be >= 1", width));
  if (bvh.size() >= kShaderMaxMeshElements || bvh.node_count() >= kShaderMaxMeshElements)
    throw InvalidArgument(fmt::format("the GL renderer takes fewer than {} triangles; the mesh has {}",
                                      kShaderMaxMeshElements, bvh.size()));
  if (bvh.depth() + 1 > static_cast<std::size_t>(kShaderBvhStackSize))
    throw InvalidArgument(fmt::format("the mesh's BVH is {} levels deep; the GL renderer's stack holds {}",
                                      bvh.depth(), kShaderBvhStackSize - 1));
  MeshTextures mesh;
  mesh.width = width;
  for (const Triangle& t : bvh.triangles()) {
    const auto& [p0, p1, p2] = t.vertices;
    put_texel(mesh.triangles, to_float(p0), t.has_normals ? 1.0f : 0.0f);
    put_texel(mesh.triangles, to_float(p1 - p0), 0);
    put_texel(mesh.triangles, to_float(p2 - p0), 0);
    for (const Vec3& n : t.normals) put_texel(mesh.triangles, to_float(n), 0);
  }
  constexpr float kInf = std::numeric_limits<float>::infinity();
  for (const Bvh::Node& node : bvh.nodes()) {
    const Vec3 &lo = node.box.min, &hi = node.box.max;
    put_texel(mesh.nodes, {rounded_toward(lo.x, -kInf), rounded_toward(lo.y, -kInf), rounded_toward(lo.z, -kInf)},
              static_cast<float>(node.first));
    put_texel(mesh.nodes, {rounded_toward(hi.x, kInf), rounded_toward(hi.y, kInf), rounded_toward(hi.z, kInf)},
              static_cast<float>(node.count));
  }
  mesh.triangle_rows = pad_rows(mesh.triangles, width);
  mesh.node_rows = pad_rows(mesh.nodes, width);
  return mesh;
}

}  // namespace specula::render
