#pragma once
// The GLSL files of src/glsl/shaders/ (compiled in by cmake/embed_assets.cmake) and a shader's text
// put together from them or from another library's embedded files (render's scene shader,
// src/render/shader_files.h). Not installed: glsl/glsl.h and render/scene_shader.h are the
// library's view.
#include <map>
#include <set>
#include <span>
#include <string>
#include <string_view>

namespace specula::glsl {

struct ShaderFile {
  std::string_view path;  ///< below the embedded folder (src/glsl/shaders/): "lobes/log.glsl"
  std::string_view text;
};

/// Every embedded file of src/glsl/shaders/, sorted by path (generated source).
std::span<const ShaderFile> embedded_shaders();

/// The file at `path` among `files`, or nullptr.
const ShaderFile* find_shader_file(std::span<const ShaderFile> files, std::string_view path) noexcept;
/// The embedded file at `path`, or nullptr.
inline const ShaderFile* find_shader_file(std::string_view path) noexcept {
  return find_shader_file(embedded_shaders(), path);
}
/// The text of the file at `path` among `files`. Throws std::logic_error if there is none.
std::string_view shader_file(std::span<const ShaderFile> files, std::string_view path);
/// The text of the embedded file at `path`. Throws std::logic_error if there is none.
inline std::string_view shader_file(std::string_view path) { return shader_file(embedded_shaders(), path); }

/// Values for a file's placeholders: `${name}` stands for values.at(name).
using Placeholders = std::map<std::string, std::string, std::less<>>;

/// `text` with each `${name}` replaced. Throws std::logic_error for a name without a value.
std::string fill(std::string_view text, const Placeholders& values);

/// A shader's text under construction: each piece once, what a file includes before the file.
/// Its files are `files` (by default the embedded src/glsl/shaders/).
class ShaderSource {
 public:
  explicit ShaderSource(Placeholders values = {}, std::span<const ShaderFile> files = embedded_shaders())
      : values_(std::move(values)), files_(files) {}

  /// Appends `text` and a newline unless a piece called `name` is already there.
  void add(std::string_view name, std::string_view text);
  /// Appends the file at `path` unless it is already there: first the files that its lines
  /// `#include "PATH"` name (in order, recursively; the lines themselves are dropped), then its
  /// text filled with the placeholders. Throws std::logic_error for a file that does not exist.
  void add_file(std::string_view path);
  std::string take() { return std::move(text_); }

 private:
  Placeholders values_;
  std::span<const ShaderFile> files_;
  std::set<std::string, std::less<>> names_;
  std::string text_;
};

}  // namespace specula::glsl
