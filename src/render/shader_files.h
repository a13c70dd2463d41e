#pragma once
// The scene shader's GLSL files, src/render/shaders/ (compiled into specula::render by
// cmake/embed_assets.cmake, as core compiles in src/glsl/shaders/): "scene/main.glsl", … Not
// installed: render/scene_shader.h is the library's view.
#include <span>

#include "src/glsl/shader_files.h"

namespace specula::render {

/// Every embedded file of src/render/shaders/, sorted by path (generated source).
std::span<const glsl::ShaderFile> embedded_shaders();

}  // namespace specula::render
