// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"; Heitz 2014; Cook & Torrance 1982 (the exact dielectric Fresnel) (docs/math.md 2 `ggx`, docs/fresnel.md).
#include "brdfs/ggx.glsl"
#include "brdfs/fresnel.glsl"
// GGX with the dielectric Fresnel; 0 below the horizon.
float specula_ggx_dielectric(vec3 N, vec3 L, vec3 V, float alpha, float eta) {
  float vh = dot(V, normalize(L + V));
  return specula_ggx_dg(N, L, V, alpha) * specula_fresnel_dielectric_eta(vh, eta);
}
