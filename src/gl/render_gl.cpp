#include "specula/gl/render_gl.h"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <set>
#include <stdexcept>
#include <string>

#include "gl_api.h"
#include "specula/render/bvh.h"
#include "specula/render/scene_shader.h"

namespace specula::gl {
namespace {

// The samplers: bound with their textures, not by set_uniforms.
const std::set<std::string> kSetElsewhere{render::scene_uniform::triangles.name, render::scene_uniform::bvh.name};

// glUniform* by name, remembering every name set.
class UniformWriter {
 public:
  explicit UniformWriter(GLuint program) : program_(program) {}

  void set(const char* name, int value) { glUniform1i(location(name), value); }
  void set(const char* name, float value) { glUniform1f(location(name), value); }
  void set(const char* name, const std::array<float, 2>& v) { glUniform2fv(location(name), 1, v.data()); }
  void set(const char* name, const std::array<float, 3>& v) { glUniform3fv(location(name), 1, v.data()); }
  void set(const char* name, const std::array<float, 4>& v) { glUniform4fv(location(name), 1, v.data()); }
  template <std::size_t N>
  void set(const char* name, const std::vector<std::array<float, N>>& values) {
    const GLint at = location(name);
    const auto count = static_cast<GLsizei>(values.size());
    if (count == 0) return;  // the shader reads only the first u_..._count elements
    if constexpr (N == 3) glUniform3fv(at, count, values[0].data());
    else glUniform4fv(at, count, values[0].data());
  }

  // A uniform the program uses that nothing set is a mismatch between this file and the shader.
  void check_all_set() const {
    GLint count = 0;
    glGetProgramiv(program_, GL_ACTIVE_UNIFORMS, &count);
    for (GLint i = 0; i < count; ++i) {
      char buffer[256];
      GLsizei length = 0;
      GLint size = 0;
      GLenum type = 0;
      glGetActiveUniform(program_, static_cast<GLuint>(i), sizeof buffer, &length, &size, &type, buffer);
      std::string name(buffer, static_cast<std::size_t>(length));
      name = name.substr(0, name.find('['));
      if (!names_.contains(name) && !kSetElsewhere.contains(name))
        throw std::logic_error(fmt::format("the scene shader's uniform {} is never set", name));
    }
  }

 private:
  GLint location(const char* name) {
    names_.insert(name);
    return glGetUniformLocation(program_, name);  // -1 (ignored by glUniform*) when optimized out
  }

  GLuint program_;
  std::set<std::string> names_;
};

// Every uniform but the samplers, by the names of render::scene_uniform (u_pixel_offset as 0, 0:
// draw_full_screen sets each tile's).
void set_uniforms(UniformWriter& w, const render::SceneUniforms& u) {
  u.visit([&](const render::SceneUniform& uniform, const auto& value) { w.set(uniform.name, value); });
}

// An RGBA32F texture read with texelFetch (nearest, no mipmaps: complete without any).
class DataTexture {
 public:
  DataTexture(int width, int rows, const std::vector<float>& texels) {
    glGenTextures(1, &id_);
    glBindTexture(GL_TEXTURE_2D, id_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, rows, 0, GL_RGBA, GL_FLOAT, texels.data());
    if (const GLenum error = glGetError(); error != GL_NO_ERROR) {
      glDeleteTextures(1, &id_);
      throw GlError(fmt::format("cannot upload a {}x{} RGBA32F mesh texture (GL error 0x{:04x})", width, rows, error));
    }
  }
  ~DataTexture() { glDeleteTextures(1, &id_); }
  DataTexture(const DataTexture&) = delete;
  DataTexture& operator=(const DataTexture&) = delete;

  void bind(GLuint program, const char* sampler, int unit) const {
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
    glBindTexture(GL_TEXTURE_2D, id_);
    glUniform1i(glGetUniformLocation(program, sampler), unit);
  }

 private:
  GLuint id_ = 0;
};

// The mesh's textures, checked against the driver's texture size.
render::MeshTextures fitting_mesh(const render::Scene& scene, const ContextInfo& info) {
  const render::MeshTextures mesh =
      render::mesh_textures(render::Bvh(scene.triangles), std::min(4096, info.max_texture_size));
  if (std::max(mesh.triangle_rows, mesh.node_rows) > info.max_texture_size)
    throw InvalidArgument(fmt::format("the mesh's {} triangles need {}x{} texels, more than {} allows ({} per side)",
                                      scene.triangles.size(), mesh.width, mesh.triangle_rows, info.renderer,
                                      info.max_texture_size));
  return mesh;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

struct Renderer::Compiled {
  Compiled(const Context& context, std::string model, render::SceneGeometry traced, const std::string& fragment)
      : model_source(std::move(model)), geometry(traced),
        program(context, render::scene_vertex_shader(glsl::Dialect::glsl330), fragment) {}

  std::string model_source;
  render::SceneGeometry geometry;
  Program program;
};

Renderer::Renderer(const Context& context, int tile_side)
    : context_(&context), tile_side_(tile_side > 0 ? tile_side : default_tile_side(context.info())) {}

Renderer::~Renderer() = default;

double Renderer::prepare(const Model& model, render::SceneGeometry geometry) {
  // The shader differs between models only in glsl::model_glsl (the rest of the text, comments with
  // the default values aside, is the same for all).
  std::string model_source = glsl::model_glsl(model);
  if (compiled_ && compiled_->model_source == model_source && compiled_->geometry == geometry) return 0;
  const auto start = std::chrono::steady_clock::now();
  compiled_.reset();
  compiled_ = std::make_unique<Compiled>(*context_, std::move(model_source), geometry,
                                         render::scene_fragment_shader(model, glsl::Dialect::glsl330, geometry));
  return milliseconds_since(start);
}

render::Image Renderer::render(const render::Scene& scene, const render::RenderSettings& settings,
                               const std::optional<render::Display>& display) {
  const render::SceneUniforms uniforms = render::scene_uniforms(scene, settings, display);
  context_->make_current();
  const render::MeshTextures mesh = fitting_mesh(scene, context_->info());
  prepare(scene.material.model, render::geometry_of(scene));
  const GLuint program = compiled_->program.id();
  glUseProgram(program);
  UniformWriter writer(program);
  set_uniforms(writer, uniforms);
  writer.check_all_set();
  const DataTexture triangles(mesh.width, mesh.triangle_rows, mesh.triangles);
  const DataTexture nodes(mesh.width, mesh.node_rows, mesh.nodes);
  triangles.bind(program, render::scene_uniform::triangles.name, 0);
  nodes.bind(program, render::scene_uniform::bvh.name, 1);
  return draw_full_screen(compiled_->program, settings.width, settings.height, tile_side_);
}

render::Image render_gl(const render::Scene& scene, const render::RenderSettings& settings) {
  render::scene_uniforms(scene, settings);  // bad input fails before a context is made
  const Context context;
  Renderer renderer(context);
  return renderer.render(scene, settings);
}

}  // namespace specula::gl
