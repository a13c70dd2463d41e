#include "specula/render/scene_shader.h"

#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>

#include "specula/brdf/directions.h"
#include "specula/exceptions.h"
#include "specula/expr/comment.h"
#include "src/render/shader_files.h"

namespace specula::render {
namespace {

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

// The default scene's value of a uniform, as its documentation shows it: an array's first element.
std::string shown(int value) { return fmt::format("{}", value); }
std::string shown(float value) { return numbers(&value, 1); }
template <std::size_t N>
std::string shown(const std::array<float, N>& values) {
  return numbers(values);
}
template <std::size_t N>
std::string shown(const std::vector<std::array<float, N>>& values) {
  return values.empty() ? "" : numbers(values.front());
}

std::string uniform_documentation(const Model& model) {
  const RenderSettings size{512, 512};
  const SceneUniforms d = scene_uniforms(default_scene(model), size);
  std::string text = fmt::format(
      "// specula scene shader: the CPU renderer's pixel (render/render.h, docs/math.md 5) with model '{}'.\n"
      "// Draw 3 vertices of scene_vertex_shader over the image (or tiles of it) and set every uniform;\n"
      "// specula's render::scene_uniforms and render::mesh_textures compute them from a scene.\n"
      "// The default scene's values at 512x512 are in brackets: a unit sphere lit from the upper left front.\n",
      expr::comment_text(model.id()));
  std::map<std::string_view, std::string> values;
  d.visit([&](const SceneUniform& u, const auto& value) { values[u.name] = shown(value); });
  for (const SceneUniform& u : scene_uniform::all) {
    const std::string declared = fmt::format("{} {}{}", u.type, u.name, u.length.empty() ? "" : "[]");
    const std::string meaning =
        fmt::format(fmt::runtime(u.meaning), fmt::arg("value", values[u.name]),
                    fmt::arg("max_spheres", kShaderMaxSpheres), fmt::arg("max_lights", kShaderMaxLights));
    text += fmt::format("//   {:<26} {}\n", declared, meaning);
  }
  return text;
}

// The lines `uniform TYPE NAME[LENGTH];` of scene_uniform::all, samplers highp.
std::string uniform_declarations() {
  std::string text;
  for (const SceneUniform& u : scene_uniform::all)
    text += fmt::format("{}uniform {}{} {}{};", text.empty() ? "" : "\n", u.type == "sampler2D" ? "highp " : "",
                        u.type, u.name, u.length.empty() ? "" : fmt::format("[{}]", u.length));
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
  return glsl::version_header(dialect) + std::string(glsl::shader_file(embedded_shaders(), "scene/vertex.glsl"));
}

std::string scene_fragment_shader(const Model& model, glsl::Dialect dialect, SceneGeometry geometry) {
  glsl::ShaderSource src({{"mesh", geometry == SceneGeometry::spheres ? "0" : "1"},
                          {"max_spheres", std::to_string(kShaderMaxSpheres)},
                          {"max_lights", std::to_string(kShaderMaxLights)},
                          {"bvh_stack", std::to_string(kShaderBvhStackSize)},
                          {"uniforms", uniform_declarations()}},
                         embedded_shaders());
  src.add_file("scene/uniforms.glsl");
  src.add("model", glsl::model_glsl(model));
  src.add_file("scene/main.glsl");
  return glsl::version_header(dialect) + uniform_documentation(model) + src.take();
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
