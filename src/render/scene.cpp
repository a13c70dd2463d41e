#include "specula/render/scene.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <limits>

#include "specula/brdf/directions.h"
#include "specula/exceptions.h"
#include "specula/io/files.h"
#include "specula/io/table.h"

namespace specula::render {
namespace {

[[noreturn]] void cannot_read(const std::filesystem::path& path, std::string_view why) {
  throw InvalidArgument(fmt::format("cannot read '{}': {}", path.string(), why));
}

bool finite(const Vec3& v) noexcept { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool valid_colour(const Rgb& c) noexcept {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b) && c.r >= 0 && c.g >= 0 && c.b >= 0;
}

std::string_view first_line(std::string_view text) {
  text = text.substr(0, text.find('\n'));
  return text.empty() ? "unreadable OBJ" : text;
}

// The statements load_obj uses, v, vn, vt and f, with every other line left blank (so that
// tinyobjloader's line numbers stay those of the file). What tinyobjloader would parse only for
// load_obj to ignore never reaches it: its `vw` (skin weight) parser converts a joint id to int
// unchecked, undefined behaviour for `vw 1 1e39 0` (found by fuzz/obj_fuzz.cpp, now in
// fuzz/corpus/obj/), and `mtllib` would open whatever file the OBJ names. Lines end at LF, CR or
// CRLF and a statement's keyword is followed by a space or tab, as tinyobjloader reads them.
std::string used_statements(std::string_view text) {
  std::string used;
  used.reserve(text.size());
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find_first_of("\r\n", start), text.size());
    const std::string_view line = text.substr(start, end - start);
    const std::size_t first = std::min(line.find_first_not_of(" \t"), line.size());
    const std::string_view statement = line.substr(first);
    const std::size_t keyword_end = statement.find_first_of(" \t");
    const std::string_view keyword = statement.substr(0, keyword_end);
    if (keyword_end != std::string_view::npos && (keyword == "v" || keyword == "vn" || keyword == "vt" || keyword == "f"))
      used += line;
    used += '\n';
    start = end + (text.substr(end, 2) == "\r\n" ? 2 : 1);
  }
  return used;
}

Vec3 obj_vertex(const std::filesystem::path& path, const std::vector<tinyobj::real_t>& values, int index,
                std::string_view what) {
  if (index < 0 || 3 * static_cast<std::size_t>(index) + 2 >= values.size())
    cannot_read(path, fmt::format("a face refers to {} {}, beyond the {} in the file", what, index + 1, values.size() / 3));
  const std::size_t i = 3 * static_cast<std::size_t>(index);
  const Vec3 v{values[i], values[i + 1], values[i + 2]};
  if (!finite(v)) cannot_read(path, fmt::format("{} {} is not finite", what, index + 1));
  return v;
}

Triangle obj_triangle(const std::filesystem::path& path, const tinyobj::attrib_t& attrib,
                      const tinyobj::index_t* corners) {
  Triangle t;
  t.has_normals = true;
  for (int k = 0; k < 3; ++k) {
    t.vertices[k] = obj_vertex(path, attrib.vertices, corners[k].vertex_index, "vertex");
    if (corners[k].normal_index < 0) {
      t.has_normals = false;
      continue;
    }
    const Vec3 n = obj_vertex(path, attrib.normals, corners[k].normal_index, "normal");
    if (!(length(n) > 0)) t.has_normals = false;
    else t.normals[k] = normalized(n);
  }
  return t;
}

void check_camera(const Camera& camera) {
  const Vec3 forward = camera.look_at - camera.position;
  if (!finite(camera.position) || !finite(camera.look_at) || !finite(camera.up) || !(length(forward) > 0))
    throw InvalidArgument("camera: position and look-at must be finite and distinct");
  if (!(length(cross(forward, camera.up)) > 1e-12 * length(forward) * length(camera.up)))
    throw InvalidArgument("camera: the up vector must not be parallel to the view direction");
  if (!(camera.vertical_fov_deg > 0 && camera.vertical_fov_deg < 180))
    throw InvalidArgument(fmt::format("camera: vertical field of view {}° is outside (0°, 180°)", camera.vertical_fov_deg));
}

}  // namespace

std::vector<Triangle> load_obj(const std::filesystem::path& path) { return parse_obj(io::read_file(path), path.string()); }

std::vector<Triangle> parse_obj(std::string_view text, std::string_view name) {
  const std::filesystem::path path(name);
  tinyobj::ObjReaderConfig config;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(used_statements(text), "", config)) cannot_read(path, first_line(reader.Error()));
  std::vector<Triangle> triangles;
  for (const auto& shape : reader.GetShapes()) {
    std::size_t offset = 0;
    for (const auto corners : shape.mesh.num_face_vertices) {
      if (corners == 3) triangles.push_back(obj_triangle(path, reader.GetAttrib(), &shape.mesh.indices[offset]));
      offset += corners;
    }
  }
  if (triangles.empty()) cannot_read(path, "no triangles in the file");
  return triangles;
}

Camera framing(const Vec3& centre, double radius, double vertical_fov_deg) {
  const double distance = 1.15 * radius / std::sin(radians(vertical_fov_deg) / 2);
  return {centre + Vec3{0, 0, distance}, centre, {0, 1, 0}, vertical_fov_deg};
}

Camera framing(const std::vector<Triangle>& triangles, double vertical_fov_deg) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Vec3 lo{inf, inf, inf}, hi = -lo;
  for (const Triangle& t : triangles)
    for (const Vec3& p : t.vertices) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
  const double radius = length(hi - lo) / 2;
  return framing((lo + hi) * 0.5, radius > 0 ? radius : 1, vertical_fov_deg);
}

void check_light(const Light& light, std::string_view what) {
  const Vec3& v = light.kind == LightKind::directional ? light.direction : light.position;
  if (!finite(v) || (light.kind == LightKind::directional && !(length(v) > 0)))
    throw InvalidArgument(fmt::format("{}: the direction must be finite and non-zero", what));
  if (!valid_colour(light.colour) || !(light.intensity >= 0) || !std::isfinite(light.intensity))
    throw InvalidArgument(fmt::format("{}: colour and intensity must be finite and ≥ 0", what));
}

std::string to_string(const Light& light) {
  const bool directional = light.kind == LightKind::directional;
  const Vec3& v = directional ? light.direction : light.position;
  auto f = [](double x) { return io::format_number(x); };
  return fmt::format("{}:{},{},{}:{},{},{}:{}", directional ? "dir" : "point", f(v.x), f(v.y), f(v.z),
                     f(light.colour.r), f(light.colour.g), f(light.colour.b), f(light.intensity));
}

Scene default_scene(const Model& model) {
  return {.camera = framing(Vec3{}, 1),
          .spheres = {Sphere{}},
          .triangles = {},
          .lights = {Light{}},
          .material = Material(model),
          .background = {}};
}

Scene make_scene(const Model& model, SceneDescription description) {
  Scene scene = default_scene(model);
  if (!description.mesh.empty()) {
    scene.spheres.clear();
    scene.triangles = std::move(description.mesh);
    scene.camera = framing(scene.triangles);
  }
  if (description.lights) scene.lights = std::move(*description.lights);
  Material& m = scene.material;
  m.diffuse = description.diffuse.value_or(m.diffuse);
  m.specular = description.specular.value_or(m.specular);
  m.ambient = description.ambient.value_or(m.ambient);
  return scene;
}

void validate(const Scene& scene) {
  check_camera(scene.camera);
  for (const Sphere& s : scene.spheres)
    if (!finite(s.centre) || !(s.radius > 0) || !std::isfinite(s.radius))
      throw InvalidArgument(fmt::format("sphere of radius {}: the centre must be finite, the radius finite and > 0", s.radius));
  if (scene.lights.size() > kMaxLights)
    throw InvalidArgument(fmt::format("{} lights; a scene takes at most {}", scene.lights.size(), kMaxLights));
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
    check_light(scene.lights[i], fmt::format("light {} ({})", i + 1, to_string(scene.lights[i])));
  const Material& m = scene.material;
  if (!valid_colour(m.diffuse) || !valid_colour(m.specular) || !valid_colour(m.ambient) || !valid_colour(scene.background))
    throw InvalidArgument("material and background colours must be finite and ≥ 0");
}

}  // namespace specula::render
