// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"; Heitz 2014; Schlick 1994 (F90 and the exponent free) (docs/math.md 2 `ggx`, docs/fresnel.md).
#include "brdfs/ggx.glsl"
#include "brdfs/fresnel.glsl"
// GGX with the schlick Fresnel; 0 below the horizon.
float specula_ggx_schlick(vec3 N, vec3 L, vec3 V, float alpha, float f0, float f90, float exponent) {
  float vh = dot(V, normalize(L + V));
  return specula_ggx_dg(N, L, V, alpha) * specula_fresnel_schlick_full(vh, f0, f90, exponent);
}
