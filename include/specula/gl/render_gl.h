#pragma once
// The GL renderer: render_cpu's image (include/specula/render/render.h) from the scene shader
// (render/scene_shader.h) run in an offscreen OpenGL context (gl/context.h), in float throughout.
#include <memory>
#include <optional>
#include <string>

#include "specula/gl/context.h"
#include "specula/render/image.h"
#include "specula/render/render.h"
#include "specula/render/scene.h"
#include "specula/render/scene_shader.h"

namespace specula::gl {

/// Renders scenes in a context it borrows, keeping the last compiled program: frames of the same
/// model (and form and coefficient) compile once. Use it from the context's thread.
class Renderer {
 public:
  /// tile_side 0: default_tile_side(context.info()). It must not outlive `context`.
  explicit Renderer(const Context& context, int tile_side = 0);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  /// Compiles and links the scene shader for `model` and `geometry` unless the current program is
  /// already that one; returns the milliseconds that took (0 when nothing was compiled). render()
  /// calls it with render::geometry_of(scene).
  double prepare(const Model& model, render::SceneGeometry geometry);

  /// The linear radiance image of `scene` (rows top-down), as render_cpu computes it but in float;
  /// with `display`, the display values of render/image.h in [0, 1] instead (sRGB-encoded, not
  /// rounded). Throws InvalidArgument as render_cpu does, and for a scene beyond the shader's
  /// limits (render::kShaderMaxSpheres, render::kShaderMaxLights, a mesh larger than the driver's
  /// textures); GlError when the driver fails.
  render::Image render(const render::Scene& scene, const render::RenderSettings& settings,
                       const std::optional<render::Display>& display = std::nullopt);

  const Context& context() const noexcept { return *context_; }

 private:
  struct Compiled;
  const Context* context_;
  int tile_side_;
  std::unique_ptr<Compiled> compiled_;
};

/// render_cpu's counterpart: a Context and a Renderer for one frame (creating the context costs
/// tens of milliseconds; keep a Renderer for many frames).
render::Image render_gl(const render::Scene& scene, const render::RenderSettings& settings);

}  // namespace specula::gl
