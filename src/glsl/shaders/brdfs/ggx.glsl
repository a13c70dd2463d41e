// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"; Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs" (docs/math.md 2 `ggx`).
#include "common/pi.glsl"
#include "brdfs/microfacet.glsl"
// GGX's D G/(4 (N.L)(N.V)) without its Fresnel: Trowbridge-Reitz D, Smith height-correlated G; 0 below the horizon.
float specula_ggx_dg(vec3 N, vec3 L, vec3 V, float alpha) {
  float nl = dot(N, L), nv = dot(N, V);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  float a2 = alpha * alpha;
  vec2 incl = specula_inclination(N, normalize(L + V));
  float q = incl.y * a2 + incl.x;
  float d = a2 / (SPECULA_PI * q * q);
  float lambda_l = 0.5 * (sqrt(1.0 + a2 * (1.0 - nl * nl) / (nl * nl)) - 1.0);
  float lambda_v = 0.5 * (sqrt(1.0 + a2 * (1.0 - nv * nv) / (nv * nv)) - 1.0);
  return d / ((1.0 + lambda_l + lambda_v) * 4.0 * nl * nv);
}
// GGX with Schlick's F.
float specula_ggx(vec3 N, vec3 L, vec3 V, float alpha, float f0) {
  return specula_ggx_dg(N, L, V, alpha) * specula_fresnel_schlick(dot(V, normalize(L + V)), f0);
}
