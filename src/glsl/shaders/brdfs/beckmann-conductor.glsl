// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"; Heitz 2014; Born & Wolf 13.2 (the exact conductor Fresnel) (docs/math.md 2 `beckmann`, docs/fresnel.md).
#include "brdfs/beckmann.glsl"
#include "brdfs/fresnel.glsl"
// Beckmann-Smith with the conductor Fresnel; 0 below the horizon.
float specula_beckmann_conductor(vec3 N, vec3 L, vec3 V, float alpha, float eta, float kappa) {
  float vh = dot(V, normalize(L + V));
  return specula_beckmann_dg(N, L, V, alpha) * specula_fresnel_conductor(vh, eta, kappa);
}
