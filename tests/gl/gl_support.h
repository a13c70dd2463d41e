#pragma once
// What the GL tests share: one OpenGL context for the whole test binary. Where EGL cannot give one,
// every test that needs it fails with the reason (GlError's message): the tests never skip.
#include "specula/gl/context.h"

namespace specula::testing {

inline const gl::Context& shared_context() {
  static const gl::Context context;  // a throw here fails the calling test; the next one tries again
  return context;
}

}  // namespace specula::testing
