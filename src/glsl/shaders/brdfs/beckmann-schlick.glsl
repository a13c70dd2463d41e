// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"; Heitz 2014; Schlick 1994 (F90 and the exponent free) (docs/math.md 2 `beckmann`, docs/fresnel.md).
#include "brdfs/beckmann.glsl"
#include "brdfs/fresnel.glsl"
// Beckmann-Smith with the schlick Fresnel; 0 below the horizon.
float specula_beckmann_schlick(vec3 N, vec3 L, vec3 V, float alpha, float f0, float f90, float exponent) {
  float vh = dot(V, normalize(L + V));
  return specula_beckmann_dg(N, L, V, alpha) * specula_fresnel_schlick_full(vh, f0, f90, exponent);
}
