#pragma once
// The CPU renderer: one primary ray through each pixel centre, local shading (docs/math.md §5,
// Figs. 10-11), shadow rays where the scene can shadow itself.
#include "specula/exceptions.h"
#include "specula/render/image.h"
#include "specula/render/scene.h"

namespace specula::render {

/// What renders an image: this CPU renderer, or OpenGL through EGL (specula/gl).
enum class Backend { cpu, gl };
inline constexpr std::size_t kBackendCount = static_cast<std::size_t>(Backend::gl) + 1;  // gl: the last

/// "cpu" or "gl" ("" outside the enum).
constexpr const char* to_string(Backend backend) noexcept {
  switch (backend) {
    case Backend::cpu: return "cpu";
    case Backend::gl: return "gl";
  }
  return "";
}
static_assert(names_complete<Backend, kBackendCount>([](Backend b) { return to_string(b); }));

struct RenderSettings {
  int width = 512;
  int height = 512;
  /// Shade each image row with one SIMD batch of the material's BRDF (simd/brdf.h, exact tier:
  /// within a few ulp of the scalar model) rather than one scalar call per pixel and light.
  bool batch_shading = true;
};

/// The linear radiance image of `scene`. Per pixel: the nearest surface along the ray through the
/// pixel centre, shaded as Material says, each light's term dropped where a shadow ray toward it
/// is blocked; the background where the ray hits nothing. Surfaces are two-sided: normals face
/// the viewer. A scene of one sphere casts no shadow rays: a convex object shadows itself exactly
/// where N·L ≤ 0, which the shading already drops.
///
/// Rows run in parallel (oneTBB); each row is shaded on its own and each pixel stored at its own
/// index, so the image is bit-identical for any thread count. With batch_shading, a row's hits are
/// found first and its BRDF values computed per light in one SIMD batch (docs/simd.md). Throws InvalidArgument for an image size
/// outside [1, kMaxImageSide] or an invalid scene (see validate).
Image render_cpu(const Scene& scene, const RenderSettings& settings);

}  // namespace specula::render
