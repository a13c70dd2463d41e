// Ward 1992, "Measuring and Modeling Anisotropic Reflection" (docs/math.md 2 `ward`): the Gaussian of the half-angle that the three normalizations of Ward's lobe share.
#include "brdfs/microfacet.glsl"
// Ward 1992 (docs/math.md 2): exp(-tan^2 d/alpha^2), d the angle between N and h = L + V (any length), a2 = alpha^2.
float specula_ward_gaussian(vec3 N, vec3 h, float a2) {
  vec2 incl = specula_inclination(N, h);
  return exp(-(incl.x / incl.y) / a2);
}
