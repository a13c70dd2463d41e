// Ward 1992, "Measuring and Modeling Anisotropic Reflection" (docs/math.md 2 `ward`): f = rho_s exp(-tan^2 d/alpha^2) / (4 pi alpha^2 sqrt((N.L)(N.V))).
#include "common/pi.glsl"
#include "brdfs/ward-gaussian.glsl"
// Ward: the paper's form; 0 below the horizon.
float specula_ward(vec3 N, vec3 L, vec3 V, float alpha, float rho_s) {
  float nl = dot(N, L), nv = dot(N, V);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  float a2 = alpha * alpha;
  return rho_s * specula_ward_gaussian(N, L + V, a2) / (4.0 * SPECULA_PI * a2 * sqrt(nl * nv));
}
