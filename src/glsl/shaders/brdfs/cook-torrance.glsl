// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces" (docs/math.md 2 `cook-torrance`): f = D F G/(4 (N.L)(N.V)), D = exp(-tan^2 d/m^2)/(pi m^2 cos^4 d), Schlick F.
#include "common/pi.glsl"
#include "brdfs/microfacet.glsl"
// Cook-Torrance with the normalized Beckmann distribution; 0 below the horizon.
float specula_cook_torrance(vec3 N, vec3 L, vec3 V, float m, float f0) {
  float nl = dot(N, L), nv = dot(N, V);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  vec3 H = normalize(L + V);
  float nh = dot(N, H), vh = dot(V, H);
  float d = specula_beckmann_unnormalized(specula_inclination(N, H), m) / SPECULA_PI;
  float g = specula_g_vcavity(nh, nv, nl, vh);
  return d * specula_fresnel_schlick(vh, f0) * g / (4.0 * nl * nv);
}
