// specula::render: the default scene rendered on the CPU, written as PNG and read back.
// Usage: uses_render OUT.png
#include <cstdio>

#include <specula/catalogue/catalogue.h>
#include <specula/render/image_io.h>
#include <specula/render/render.h>
#include <specula/render/scene.h>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const specula::render::Scene scene = specula::render::default_scene(specula::make_model("ggx"));
  const specula::render::Image image = specula::render::render_cpu(scene, {32, 32});
  specula::render::write_png(argv[1], image, specula::render::Display{});
  const specula::render::ImageFile back = specula::render::read_png(argv[1]);
  std::printf("render: %dx%d, centre radiance %.4f, PNG read back %dx%d\n", image.width(), image.height(),
              image.at(16, 16).r, back.image.width(), back.image.height());
  return back.image.width() == 32 ? 0 : 1;
}
