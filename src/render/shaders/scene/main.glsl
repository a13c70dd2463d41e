// The scene shader's fragment stage: render/render.cpp's pixel (PinholeRays, the nearest surface, its shading), docs/math.md 5.
// Needs scene/uniforms.glsl and the model's specula_brdf (gl/glsl.h) before it.
#include "scene/shading.glsl"
#include "scene/display.glsl"
// render.cpp PinholeRays: the ray through the pixel centre; gl_FragCoord counts rows from the bottom, so sy = 2 y/h - 1 is the CPU's 1 - 2(row + 0.5)/h once the image is flipped.
void main() {
  vec2 s = 2.0 * (gl_FragCoord.xy + u_pixel_offset) / u_resolution - 1.0;
  vec3 direction = normalize(u_forward + u_right * s.x + u_up * s.y);
  SceneSurface surface;
  vec3 radiance = scene_closest(u_eye, direction, surface) ? scene_surface_radiance(surface, -direction) : u_background;
  scene_colour = vec4(u_display == 1 ? scene_display(radiance) : radiance, 1.0);
}
