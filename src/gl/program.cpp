// Programs and the full-screen pass of include/specula/gl/context.h.
#include <algorithm>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "gl_api.h"
#include "specula/gl/context.h"
#include "target.h"

namespace specula::gl {
namespace {

// The driver's log on one line: newlines become "; ", trailing blanks go.
std::string one_line(std::string log) {
  while (!log.empty() && (log.back() == '\n' || log.back() == ' ' || log.back() == '\0')) log.pop_back();
  std::string line;
  for (char c : log) line += c == '\n' ? std::string("; ") : std::string(1, c);
  return line.empty() ? "no log" : line;
}

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return one_line(log);
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return one_line(log);
}

GLuint compile(GLenum stage, std::string_view source) {
  const GLuint shader = glCreateShader(stage);
  const GLchar* text = source.data();
  const auto length = static_cast<GLint>(source.size());
  glShaderSource(shader, 1, &text, &length);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return shader;
  const std::string log = shader_log(shader);
  glDeleteShader(shader);
  throw GlError(fmt::format("the {} shader does not compile: {}", stage == GL_VERTEX_SHADER ? "vertex" : "fragment", log));
}

// The tile's RGBA rows (bottom-up, `width` pixels each) into the image's RGB rows (top-down).
void store_tile(const std::vector<float>& rgba, int x0, int y0, int width, int height, render::Image& image) {
  const auto samples = image.samples();
  for (int row = 0; row < height; ++row) {
    const int image_row = image.height() - 1 - (y0 + row);
    const float* from = &rgba[4 * static_cast<std::size_t>(row) * static_cast<std::size_t>(width)];
    float* to = &samples[3 * (static_cast<std::size_t>(image_row) * static_cast<std::size_t>(image.width()) +
                              static_cast<std::size_t>(x0))];
    for (int x = 0; x < width; ++x, from += 4, to += 3) std::copy(from, from + 3, to);
  }
}

}  // namespace

Program::Program(const Context& context, std::string_view vertex_source, std::string_view fragment_source)
    : context_(&context) {
  context.make_current();
  const GLuint vertex = compile(GL_VERTEX_SHADER, vertex_source);
  GLuint fragment = 0;
  try {
    fragment = compile(GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    glDeleteShader(vertex);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vertex);
  glAttachShader(id_, fragment);
  glLinkProgram(id_);
  glDeleteShader(vertex);  // flagged; freed with the program
  glDeleteShader(fragment);
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return;
  const std::string log = program_log(id_);
  glDeleteProgram(id_);
  throw GlError("the program does not link: " + log);
}

Program::~Program() {
  try {
    context_->make_current();
    glDeleteProgram(id_);
  } catch (const GlError&) {
    // The context is gone with its programs; nothing is left to free.
  }
}

int default_tile_side(const ContextInfo& info) noexcept {
  return std::max(1, std::min({2048, info.max_texture_size, info.max_viewport_width, info.max_viewport_height}));
}

render::Image draw_full_screen(const Program& program, int width, int height, int tile_side) {
  render::Image image(width, height);
  if (tile_side < 1) throw InvalidArgument(fmt::format("tile side {} is invalid: it must be ≥ 1", tile_side));
  program.context().make_current();
  const int tile_width = std::min(width, tile_side), tile_height = std::min(height, tile_side);
  Target& target = program.context().target(tile_width, tile_height);
  std::vector<float>& rgba = target.readback();
  glUseProgram(program.id());
  const GLint offset = glGetUniformLocation(program.id(), "u_pixel_offset");
  for (int y0 = 0; y0 < height; y0 += tile_height)
    for (int x0 = 0; x0 < width; x0 += tile_width) {
      const int w = std::min(tile_width, width - x0), h = std::min(tile_height, height - y0);
      glViewport(0, 0, w, h);
      glUniform2f(offset, static_cast<float>(x0), static_cast<float>(y0));
      glDrawArrays(GL_TRIANGLES, 0, 3);
      glReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
      store_tile(rgba, x0, y0, w, h, image);
    }
  if (const GLenum error = glGetError(); error != GL_NO_ERROR)
    throw GlError(fmt::format("OpenGL error 0x{:04x} while drawing a {}x{} image", error, width, height));
  return image;
}

}  // namespace specula::gl
