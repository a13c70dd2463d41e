// specula::gl: the default scene rendered by the EGL renderer (offscreen; Mesa's llvmpipe will do).
#include <cstdio>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include <specula/gl/render_gl.h>
#include <specula/catalogue/catalogue.h>
#include <specula/render/scene.h>

int main() {
  const specula::render::Scene scene = specula::render::default_scene(specula::make_model("ggx"));
  const specula::render::Image image = specula::gl::render_gl(scene, {32, 32});
  std::printf("gl: %dx%d, centre radiance %.4f\n", image.width(), image.height(), image.at(16, 16).r);
#if defined(__SANITIZE_ADDRESS__)
  __lsan_do_leak_check();  // now, while Mesa's threads are idle (as specula's own main does)
#endif
  return image.at(16, 16).r > 0 ? 0 : 1;
}
