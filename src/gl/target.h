#pragma once
// A float RGBA colour target: a texture attached to a framebuffer object, kept by its Context
// from one draw to the next (a new 16 MiB target per frame costs llvmpipe up to 10x the draw).
#include <fmt/format.h>
#include <vector>

#include "gl_api.h"
#include "specula/gl/context.h"

namespace specula::gl {

class Target {
 public:
  /// Needs the context current; leaves the framebuffer bound and the active unit's texture as it was.
  Target(int width, int height) : width_(width), height_(height) {
    GLint bound = 0;  // a program's input textures stay bound
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width, height, 0, GL_RGBA, GL_FLOAT, nullptr);
    glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound));
    glGenFramebuffers(1, &framebuffer_);
    bind();
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    const GLenum error = glGetError();
    if (status != GL_FRAMEBUFFER_COMPLETE || error != GL_NO_ERROR) {
      release();
      throw GlError(fmt::format("cannot make a {}x{} RGBA32F render target (framebuffer status 0x{:04x}, GL error 0x{:04x})",
                                width, height, status, error));
    }
    rgba_.resize(4 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  }
  ~Target() { release(); }
  Target(const Target&) = delete;
  Target& operator=(const Target&) = delete;

  int width() const noexcept { return width_; }
  int height() const noexcept { return height_; }
  void bind() const noexcept { glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_); }
  /// Room for glReadPixels of the whole target as RGBA floats.
  std::vector<float>& readback() noexcept { return rgba_; }

 private:
  void release() noexcept {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &texture_);
  }

  int width_, height_;
  GLuint texture_ = 0;
  GLuint framebuffer_ = 0;
  std::vector<float> rgba_;
};

}  // namespace specula::gl
