// Lambert 1760, "Photometria" (docs/math.md 2 `lambert`): f = rho/pi.
#include "common/pi.glsl"
// Lambert: the ideal diffuse reflector; 0 below the horizon.
float specula_lambert(vec3 N, vec3 L, vec3 V, float rho) {
  float nl = dot(N, L), nv = dot(N, V);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  return rho / SPECULA_PI;
}
