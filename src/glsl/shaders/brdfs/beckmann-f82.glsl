// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"; Heitz 2014; Hoffman 2019, "Fresnel Equations Considered Harmful" (F82-tint) (docs/math.md 2 `beckmann`, docs/fresnel.md).
#include "brdfs/beckmann.glsl"
#include "brdfs/fresnel.glsl"
// Beckmann-Smith with the f82 Fresnel; 0 below the horizon.
float specula_beckmann_f82(vec3 N, vec3 L, vec3 V, float alpha, float f0, float tint) {
  float vh = dot(V, normalize(L + V));
  return specula_beckmann_dg(N, L, V, alpha) * specula_fresnel_f82(vh, f0, tint);
}
