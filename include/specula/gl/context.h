#pragma once
// An offscreen OpenGL 3.3 core context through EGL (no window, no surface), the programs that run
// in it and the full-screen pass that turns a fragment shader into a linear float image.
//
// The display: a hardware EGL device when EGL_EXT_device_enumeration + EGL_EXT_platform_device
// list one (a device without EGL_MESA_device_software), else Mesa's surfaceless platform
// (llvmpipe on a machine without a GPU). The environment variable SPECULA_EGL_PLATFORM=device or
// =surfaceless tries only that kind. Part of the separate library specula_gl, which links
// libEGL and libOpenGL (glvnd); no other specula library needs either.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "specula/exceptions.h"
#include "specula/render/image.h"

namespace specula::gl {

/// What OpenGL cannot do here: no EGL display, no 3.3 core context, a shader that does not compile
/// or link (with the driver's log), a target the driver cannot allocate. One line of text.
class GlError : public InvalidArgument {
 public:
  using InvalidArgument::InvalidArgument;
};

class Program;
class Target;
struct GlslFunction;

struct ContextInfo {
  std::string platform;  ///< how the display was found, e.g. "Mesa surfaceless" or "EGL device /dev/dri/renderD128"
  std::string vendor;    ///< GL_VENDOR
  std::string renderer;  ///< GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version;   ///< GL_VERSION
  int max_texture_size = 0;
  int max_viewport_width = 0;
  int max_viewport_height = 0;
};

/// "renderer (version; platform)", one line for --verbose and benchmark labels.
std::string to_string(const ContextInfo& info);

/// An OpenGL 3.3 core profile context, current on the thread that created it. Use it (and the
/// Programs made in it) from one thread at a time; make_current() moves it to the calling thread.
class Context {
 public:
  /// Throws GlError naming why each display that was tried failed, or for an unknown
  /// SPECULA_EGL_PLATFORM.
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const ContextInfo& info() const noexcept { return info_; }
  void make_current() const;

 private:
  friend render::Image draw_full_screen(const Program& program, int width, int height, int tile_side);
  friend std::vector<double> time_functions(const Context& context, const std::vector<GlslFunction>& functions, int trials);
  /// The colour target of that size, kept for the next draw of the same size; current and bound.
  Target& target(int width, int height) const;

  struct Egl;
  std::unique_ptr<Egl> egl_;
  ContextInfo info_;
};

/// A linked vertex + fragment program. Throws GlError with the stage and the driver's info log
/// (on one line) when a stage does not compile or the program does not link.
class Program {
 public:
  /// It must not outlive `context`.
  Program(const Context& context, std::string_view vertex_source, std::string_view fragment_source);
  ~Program();
  Program(const Program&) = delete;
  Program& operator=(const Program&) = delete;

  /// The GL program name, for glUniform* (the context must be current).
  unsigned id() const noexcept { return id_; }
  const Context& context() const noexcept { return *context_; }

 private:
  const Context* context_;
  unsigned id_ = 0;
};

/// The largest tile draw_full_screen uses on a side: 2048 (64 MiB of RGBA32F per tile), or less if
/// the driver's viewport or texture limits are smaller.
int default_tile_side(const ContextInfo& info) noexcept;

/// Runs `program` (its uniforms already set, a full-screen triangle from gl_VertexID as its vertex
/// shader) once per pixel of a width × height image, in tiles of at most tile_side² pixels,
/// and reads the RGB of its output back as floats, row 0 at the top. Before each tile's draw
/// the uniform vec2 `u_pixel_offset` (if the program uses it) is set to the tile's lower-left
/// pixel in the whole image, counted from the bottom left as gl_FragCoord is: the program adds it
/// to gl_FragCoord.xy. Throws InvalidArgument for a size outside [1, render::kMaxImageSide] or a
/// tile_side < 1, GlError when the driver fails.
render::Image draw_full_screen(const Program& program, int width, int height, int tile_side);

}  // namespace specula::gl
