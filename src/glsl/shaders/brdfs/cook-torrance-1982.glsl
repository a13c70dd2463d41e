// Cook & Torrance 1982, "A Reflectance Model for Computer Graphics" (docs/math.md 2 `cook-torrance-1982`): f = D F G/(pi (N.L)(N.V)), D = exp(-tan^2 d/m^2)/(m^2 cos^4 d), dielectric F.
#include "common/pi.glsl"
#include "brdfs/microfacet.glsl"
// Cook & Torrance 1982, eq. 8 (docs/math.md 2): unpolarized dielectric Fresnel, eta = (1 + sqrt F0)/(1 - sqrt F0); F0 = 1 gives F = 1.
float specula_fresnel_dielectric(float vh, float f0) {
  if (f0 >= 1.0) return 1.0;
  float r = sqrt(f0);
  float eta = (1.0 + r) / (1.0 - r);
  float g = sqrt(eta * eta + vh * vh - 1.0);
  float a = (g - vh) / (g + vh);
  float b = (vh * (g + vh) - 1.0) / (vh * (g - vh) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}
// Cook-Torrance, the paper's 1982 form; 0 below the horizon.
float specula_cook_torrance_1982(vec3 N, vec3 L, vec3 V, float m, float f0) {
  float nl = dot(N, L), nv = dot(N, V);
  if (nl <= 0.0 || nv <= 0.0) return 0.0;
  vec3 H = normalize(L + V);
  float nh = dot(N, H), vh = dot(V, H);
  float d = specula_beckmann_unnormalized(specula_inclination(N, H), m);
  float g = specula_g_vcavity(nh, nv, nl, vh);
  return d * specula_fresnel_dielectric(vh, f0) * g / (SPECULA_PI * nl * nv);
}
