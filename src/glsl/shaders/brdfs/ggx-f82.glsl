// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"; Heitz 2014; Hoffman 2019, "Fresnel Equations Considered Harmful" (F82-tint) (docs/math.md 2 `ggx`, docs/fresnel.md).
#include "brdfs/ggx.glsl"
#include "brdfs/fresnel.glsl"
// GGX with the f82 Fresnel; 0 below the horizon.
float specula_ggx_f82(vec3 N, vec3 L, vec3 V, float alpha, float f0, float tint) {
  float vh = dot(V, normalize(L + V));
  return specula_ggx_dg(N, L, V, alpha) * specula_fresnel_f82(vh, f0, tint);
}
