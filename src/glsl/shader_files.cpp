#include "src/glsl/shader_files.h"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>

namespace specula::glsl {

const ShaderFile* find_shader_file(std::span<const ShaderFile> files, std::string_view path) noexcept {
  const auto it = std::find_if(files.begin(), files.end(), [&](const ShaderFile& f) { return f.path == path; });
  return it == files.end() ? nullptr : &*it;
}

std::string_view shader_file(std::span<const ShaderFile> files, std::string_view path) {
  const ShaderFile* file = find_shader_file(files, path);
  if (!file) throw std::logic_error(fmt::format("no embedded shader file '{}'", path));
  return file->text;
}

std::string fill(std::string_view text, const Placeholders& values) {
  std::string out;
  for (std::size_t at = 0;;) {
    const std::size_t open = text.find("${", at);
    out += text.substr(at, open == std::string_view::npos ? open : open - at);
    if (open == std::string_view::npos) return out;
    const std::size_t close = text.find('}', open);
    const std::string_view name = text.substr(open + 2, close == std::string_view::npos ? close : close - open - 2);
    const auto value = values.find(name);
    if (close == std::string_view::npos || value == values.end())
      throw std::logic_error(fmt::format("shader placeholder '${{{}}}' has no value", name));
    out += value->second;
    at = close + 1;
  }
}

void ShaderSource::add(std::string_view name, std::string_view text) {
  if (!names_.emplace(name).second) return;
  text_ += text;
  text_ += '\n';
}

void ShaderSource::add_file(std::string_view path) {
  if (!names_.emplace(path).second) return;
  constexpr std::string_view kInclude = "#include \"";
  std::string body;
  const std::string_view text = shader_file(files_, path);
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line = text.substr(at, end - at);
    if (line.starts_with(kInclude) && line.ends_with('"'))
      add_file(line.substr(kInclude.size(), line.size() - kInclude.size() - 1));
    else
      (body += line) += '\n';
    at = end + 1;
  }
  text_ += fill(body, values_);
}

}  // namespace specula::glsl
