// Duer 2006, "An Improved Normalization for the Ward Reflectance Model" (docs/math.md 2 `ward-duer`): f = rho_s exp(-tan^2 d/alpha^2) / (4 pi alpha^2 (N.L)(N.V)).
#include "common/pi.glsl"
#include "brdfs/ward-gaussian.glsl"
// Ward, Duer's normalization: (N.L)(N.V) in place of its square root; 0 below the horizon.
float specula_ward_duer(vec3 N, vec3 L, vec3 V, float alpha, float rho_s) {
  float nl = dot(N, L), nv = dot(N, V);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  float a2 = alpha * alpha;
  return rho_s * specula_ward_gaussian(N, L + V, a2) / (4.0 * SPECULA_PI * a2 * nl * nv);
}
