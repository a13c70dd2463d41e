// Fuzzes the OBJ mesh loader (render::load_obj, include/specula/render/scene.h; `specula render
// --scene`), which reads the file with tinyobjloader, and what a render does first with the
// mesh: the camera framing and the BVH. Input: the OBJ file's bytes, written to a scratch file
// (load_obj takes a path). Properties, each a finding when broken:
//   - load_obj() returns or throws InvalidArgument, nothing else;
//   - what it returns is non-empty, every vertex finite, every vertex normal (when has_normals)
//     of unit length;
//   - framing() gives a finite camera; the BVH holds every triangle and its ray hits lie
//     inside the ray's interval with finite barycentric weights.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "fuzz_support.h"
#include "specula/render/bvh.h"
#include "specula/render/scene.h"

namespace {

using namespace specula;
using specula::Vec3;

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// One scratch directory per process, removed at exit: load_obj resolves an mtllib beside the file.
struct Scratch {
  Scratch()
      : dir(std::filesystem::temp_directory_path() / ("specula-obj-fuzz-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::filesystem::path dir;
};

std::filesystem::path write_input(std::string_view bytes) {
  static const Scratch scratch;
  const auto path = scratch.dir / "mesh.obj";
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  fuzz::require(out.good(), "cannot write the scratch OBJ file " + path.string());
  return path;
}

void check_mesh(const std::vector<render::Triangle>& triangles) {
  fuzz::require(!triangles.empty(), "load_obj returned no triangles");
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      fuzz::require(finite(t.vertices[k]), "load_obj returned a non-finite vertex");
      if (t.has_normals)
        fuzz::require(std::abs(length(t.normals[k]) - 1) <= 1e-9, "load_obj returned a normal that is not unit length");
    }
  }
  const render::Camera camera = render::framing(triangles);
  fuzz::require(finite(camera.position) && finite(camera.look_at), "framing() of a loaded mesh is not finite");

  const render::Bvh bvh(triangles);
  fuzz::require(bvh.size() == triangles.size(), "the BVH lost triangles");
  const Vec3 directions[] = {{0, 0, -1}, {0.6, -0.48, -0.64}, {-1, 0, 0}};
  for (const Vec3& d : directions) {
    const render::Ray ray{camera.position, d};
    const double t_max = 1e6;
    if (const auto hit = bvh.closest(ray, 0, t_max)) {
      fuzz::require(hit->t > 0 && hit->t < t_max, "a BVH hit lies outside the ray's interval");
      fuzz::require(std::isfinite(hit->u) && std::isfinite(hit->v), "a BVH hit has non-finite barycentric weights");
      fuzz::require(bvh.occluded(ray, 0, t_max), "closest() hits but occluded() does not");
    }
    const render::Ray from_centre{camera.look_at, d};
    (void)bvh.closest(from_centre);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = write_input(fuzz::text_of(data, size));
  std::vector<render::Triangle> triangles;
  if (fuzz::accepted("load_obj", [&] { triangles = render::load_obj(path); }))
    fuzz::require(fuzz::accepted("framing and BVH", [&] { check_mesh(triangles); }),
                  "framing or the BVH threw InvalidArgument for a mesh load_obj accepted");
  return 0;
}
