#pragma once
// The meshes and environment probes of the lab's lit-object view (docs/serve.md): the bundled ones
// (web/assets/knot.obj, web/assets/sky.exr) and the page's uploads (POST /api/upload/obj and
// /api/upload/probe), each parsed and checked once and then kept by id for the environment jobs.
// Only the newest Limits::max_kept_uploads uploads are kept; an older id is gone (404).
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "specula/render/environment.h"
#include "specula/render/scene.h"
#include "specula/serve/api.h"

namespace specula::serve {

using Mesh = std::vector<render::Triangle>;

class Uploads {
 public:
  explicit Uploads(const Limits& limits) : limits_(limits) {}

  /// Parses an OBJ upload and keeps it: {"obj": id, "triangles": n}. Throws InvalidField "body"
  /// (400) for a malformed file or more than Limits::max_upload_triangles triangles.
  std::string add_obj(std::string_view text);
  /// Decodes a PNG or EXR upload and keeps it as a latitude-longitude probe: {"probe": id, "width",
  /// "height"}. Throws InvalidArgument (400) for a malformed image, one of more than
  /// Limits::max_probe_pixels pixels, or a NaN, infinite or negative pixel.
  std::string add_probe(std::string_view bytes);

  /// "sphere" (nullptr: the default scene's unit sphere), "bundled", or an upload's id; InvalidField
  /// `field` for anything else.
  std::shared_ptr<const Mesh> mesh(std::string_view id, std::string_view field) const;
  /// "furnace" (the white furnace), "bundled", or an upload's id; InvalidField `field` otherwise.
  std::shared_ptr<const render::Environment> probe(std::string_view id, std::string_view field) const;

 private:
  template <class T>
  std::string keep(std::map<std::int64_t, std::shared_ptr<const T>>& kept, std::shared_ptr<const T> item);

  const Limits& limits_;
  mutable std::mutex mutex_;
  std::int64_t next_id_ = 1;
  std::map<std::int64_t, std::shared_ptr<const Mesh>> meshes_;
  std::map<std::int64_t, std::shared_ptr<const render::Environment>> probes_;
};

}  // namespace specula::serve
