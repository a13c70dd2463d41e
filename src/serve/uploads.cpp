#include "uploads.h"

#include <charconv>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "assets.h"
#include "specula/exceptions.h"
#include "specula/render/image_io.h"

namespace specula::serve {
namespace {

std::string_view asset_bytes(std::string_view path) {
  const Asset* asset = find_asset(path);
  if (!asset) throw std::logic_error(fmt::format("the bundled asset {} is missing", path));
  return asset->bytes;
}

std::shared_ptr<const Mesh> bundled_mesh() {
  static const auto mesh = std::make_shared<const Mesh>(render::parse_obj(asset_bytes("/assets/knot.obj"), "knot.obj"));
  return mesh;
}

std::shared_ptr<const render::Environment> bundled_probe() {
  static const auto probe = std::make_shared<const render::Environment>(
      render::Environment::lat_long(render::decode_image(asset_bytes("/assets/sky.exr"), "sky.exr").image));
  return probe;
}

/// "obj-12" → 12 for the prefix "obj-"; 0 for anything else.
std::int64_t id_number(std::string_view id, std::string_view prefix) {
  if (!id.starts_with(prefix)) return 0;
  const std::string_view digits = id.substr(prefix.size());
  std::int64_t n = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), n);
  return ec == std::errc() && end == digits.data() + digits.size() && n > 0 ? n : 0;
}

template <class T>
std::shared_ptr<const T> find(const std::map<std::int64_t, std::shared_ptr<const T>>& kept, std::int64_t id) {
  const auto it = kept.find(id);
  return it == kept.end() ? nullptr : it->second;
}

}  // namespace

template <class T>
std::string Uploads::keep(std::map<std::int64_t, std::shared_ptr<const T>>& kept, std::shared_ptr<const T> item) {
  const std::lock_guard lock(mutex_);
  const std::int64_t id = next_id_++;
  kept.emplace(id, std::move(item));
  while (kept.size() > limits_.max_kept_uploads) kept.erase(kept.begin());
  return std::to_string(id);
}

std::string Uploads::add_obj(std::string_view text) {
  auto mesh = std::make_shared<const Mesh>(render::parse_obj(text, "the OBJ"));
  if (mesh->size() > limits_.max_upload_triangles)
    throw InvalidField("body", fmt::format("the OBJ has {} triangles; at most {}", mesh->size(), limits_.max_upload_triangles));
  const std::size_t triangles = mesh->size();
  const std::string id = "obj-" + keep(meshes_, std::move(mesh));
  return nlohmann::ordered_json{{"obj", id}, {"triangles", triangles}}.dump() + "\n";
}

std::string Uploads::add_probe(std::string_view bytes) {
  const render::Image image = render::decode_image(bytes, "the probe", limits_.max_probe_pixels).image;
  const int width = image.width(), height = image.height();
  auto probe = std::make_shared<const render::Environment>(render::Environment::lat_long(image));
  const std::string id = "probe-" + keep(probes_, std::move(probe));
  return nlohmann::ordered_json{{"probe", id}, {"width", width}, {"height", height}}.dump() + "\n";
}

std::shared_ptr<const Mesh> Uploads::mesh(std::string_view id, std::string_view field) const {
  if (id == "sphere") return nullptr;
  if (id == "bundled") return bundled_mesh();
  const std::lock_guard lock(mutex_);
  if (const auto mesh = find(meshes_, id_number(id, "obj-"))) return mesh;
  throw InvalidField(std::string(field), fmt::format("{} '{}' is not sphere, bundled or a kept upload's id (the newest {} are kept)",
                                                     field, id, limits_.max_kept_uploads));
}

std::shared_ptr<const render::Environment> Uploads::probe(std::string_view id, std::string_view field) const {
  if (id == "furnace") return std::make_shared<const render::Environment>(render::Environment::uniform({1, 1, 1}));
  if (id == "bundled") return bundled_probe();
  const std::lock_guard lock(mutex_);
  if (const auto probe = find(probes_, id_number(id, "probe-"))) return probe;
  throw InvalidField(std::string(field), fmt::format("{} '{}' is not furnace, bundled or a kept upload's id (the newest {} are kept)",
                                                     field, id, limits_.max_kept_uploads));
}

}  // namespace specula::serve
