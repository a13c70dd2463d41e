// The paper's local illumination (Romanyuk et al. 2023, Figs. 10-11; docs/math.md 5): the shading equation of every specula GL shader, as render/render.cpp's shade() on the CPU.
// Needs scene/uniforms.glsl and the model's specula_brdf (gl/glsl.h) before it.
#include "scene/geometry.glsl"
// render.cpp, Shader::in_shadow: a light below the face is blocked by the face itself; else a shadow ray from just above the face toward the light.
bool scene_in_shadow(SceneSurface s, vec3 L, float distance) {
  if (dot(s.geometric, L) <= 0.0) return true;
  vec3 origin = scene_offset_ray(s.point, s.geometric);
  return scene_occluded(origin, L, distance - length(origin - s.point));
}

// docs/math.md 5 (the paper's local illumination, render/render.cpp shade()): L_o = ambient rho_d + sum over lights of (rho_d/pi + rho_s f(N, L, V)) E max(0, N.L), lights at N.L <= 0 or in shadow dropped. Shadow rays only where the CPU casts them: more than one sphere, or a mesh.
vec3 scene_surface_radiance(SceneSurface s, vec3 V) {
  vec3 sum = u_ambient * u_diffuse;
  bool shadows = u_triangle_count > 0 || u_sphere_count > 1;
  for (int i = 0; i < u_light_count; ++i) {
    vec3 L = u_lights[i].xyz;
    vec3 E = u_light_irradiance[i];
    float distance = SCENE_FAR;
    if (u_lights[i].w > 0.5) {  // point light: E = colour intensity / d^2
      vec3 to_light = u_lights[i].xyz - s.point;
      float d2 = dot(to_light, to_light);
      distance = sqrt(d2);
      L = to_light / distance;
      E = E / d2;
    }
    float cos_i = dot(s.normal, L);
    if (cos_i <= 0.0 || (shadows && scene_in_shadow(s, L, distance))) continue;
    sum += (u_diffuse * SCENE_INV_PI + u_specular * specula_brdf(s.normal, L, V, u_model_params)) * E * cos_i;
  }
  return sum;
}
