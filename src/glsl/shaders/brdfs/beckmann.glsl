// Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces", eq. 25-27; Heitz 2014 (docs/math.md 2 `beckmann`).
#include "common/pi.glsl"
#include "brdfs/microfacet.glsl"
${erfc_function}
// Smith's Lambda of Beckmann at cos theta = c: (exp(-a^2)/(a sqrt(pi)) - erfc(a))/2, a = cot theta / alpha.
float specula_beckmann_lambda(float c, float alpha) {
  float s = sqrt(max(0.0, 1.0 - c * c));
  if (s <= 0.0) return 0.0;
  float a = c / (alpha * s);
  return max(0.0, 0.5 * (exp(-a * a) / (a * sqrt(SPECULA_PI)) - specula_erfc(a)));
}
// Beckmann's D G/(4 (N.L)(N.V)) without its Fresnel: D = exp(-tan^2 d/alpha^2)/(pi alpha^2 cos^4 d), Smith height-correlated G; 0 below the horizon.
float specula_beckmann_dg(vec3 N, vec3 L, vec3 V, float alpha) {
  float nl = dot(N, L), nv = dot(N, V);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  float d = specula_beckmann_unnormalized(specula_inclination(N, normalize(L + V)), alpha) / SPECULA_PI;
  float g = 1.0 / (1.0 + specula_beckmann_lambda(nl, alpha) + specula_beckmann_lambda(nv, alpha));
  return d * g / (4.0 * nl * nv);
}
// Beckmann-Smith with Schlick's F.
float specula_beckmann(vec3 N, vec3 L, vec3 V, float alpha, float f0) {
  return specula_beckmann_dg(N, L, V, alpha) * specula_fresnel_schlick(dot(V, normalize(L + V)), f0);
}
