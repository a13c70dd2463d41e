// Schlick 1994; Hoffman 2019, "Fresnel Equations Considered Harmful"; Born & Wolf, "Principles of Optics" 13.2: the Fresnel kinds of the microfacet models (docs/fresnel.md).
// Schlick 1994 with F90 and the exponent free: F0 + (F90 - F0)(1 - c)^p.
float specula_fresnel_schlick_full(float c, float f0, float f90, float p) {
  return f0 + (f90 - f0) * pow(clamp(1.0 - c, 0.0, 1.0), p);
}
// Hoffman 2019: Schlick's F minus b c (1 - c)^6, b making F at c = 1/7 Schlick's times the tint; clamped to [0, 1].
float specula_fresnel_f82(float c, float f0, float tint) {
  const float s = 6.0 / 7.0;
  float s5 = s * s * s * s * s;
  float b = (f0 + (1.0 - f0) * s5) * (1.0 - tint) / (s5 * s / 7.0);
  float m = clamp(1.0 - c, 0.0, 1.0);
  float m2 = m * m;
  float m5 = m2 * m2 * m;
  return clamp(f0 + (1.0 - f0) * m5 - b * c * m5 * m, 0.0, 1.0);
}
// Cook & Torrance 1982 eq. 8 from either side, eta = n_t / n_i: total internal reflection where g^2 <= 0.
float specula_fresnel_dielectric_eta(float c, float eta) {
  c = clamp(c, 0.0, 1.0);
  float g2 = eta * eta - 1.0 + c * c;
  if (g2 <= 0.0) return 1.0;
  float g = sqrt(g2);
  float a = (g - c) / (g + c), b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
  return 0.5 * a * a * (1.0 + b * b);
}
// Born & Wolf 13.2 in real arithmetic (as pbrt-v3's FrConductor): the conductor of index eta + i kappa.
float specula_fresnel_conductor(float c, float eta, float kappa) {
  c = clamp(c, 0.0, 1.0);
  float c2 = c * c, s2 = 1.0 - c2;
  float t0 = eta * eta - kappa * kappa - s2;
  float a2b2 = sqrt(t0 * t0 + 4.0 * eta * eta * kappa * kappa);
  float a = sqrt(max(0.5 * (a2b2 + t0), 0.0));
  float t1 = a2b2 + c2, t2 = 2.0 * a * c;
  float rs = (t1 - t2) / (t1 + t2);
  float t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
  float rp = rs * (t3 - t4) / (t3 + t4);
  return min(1.0, 0.5 * (rs + rp));
}
