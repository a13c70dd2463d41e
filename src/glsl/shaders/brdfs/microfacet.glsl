// Cook & Torrance 1982, "A Reflectance Model for Computer Graphics", and Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering": the microfacet parts the full BRDFs share (docs/math.md 2).
// docs/math.md 2, Cook-Torrance parts: (sin^2, cos^2) of the angle between unit N and h of any length; sin^2 from |N x h|^2, exact near 0.
vec2 specula_inclination(vec3 N, vec3 h) {
  vec3 s = cross(N, h);
  float c = dot(N, h);
  return vec2(dot(s, s), c * c) / dot(h, h);
}
// Cook & Torrance 1982 (docs/math.md 2): Beckmann's exp(-tan^2 d/m^2)/(m^2 cos^4 d), without the 1/pi of a normalized NDF.
float specula_beckmann_unnormalized(vec2 incl, float m) {
  float m2 = m * m;
  return exp(-(incl.x / incl.y) / m2) / (m2 * incl.y * incl.y);
}
// Cook & Torrance 1982 (docs/math.md 2): V-cavity masking-shadowing G = min(1, 2(N.H)(N.V)/(V.H), 2(N.H)(N.L)/(V.H)).
float specula_g_vcavity(float nh, float nv, float nl, float vh) {
  return min(1.0, min(2.0 * nh * nv / vh, 2.0 * nh * nl / vh));
}
// Schlick 1994 (docs/math.md 2): F = F0 + (1 - F0)(1 - V.H)^5.
float specula_fresnel_schlick(float vh, float f0) {
  float m = 1.0 - vh;
  float m2 = m * m;
  return f0 + (1.0 - f0) * m2 * m2 * m;
}
