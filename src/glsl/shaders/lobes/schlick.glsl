// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering" (docs/math.md 2 `schlick`): F = c/(n - n c + c), a rational approximation of c^n.
float specula_schlick_lobe(float c, float n) {
  c = clamp(c, 0.0, 1.0);
  return c / (n * (1.0 - c) + c);
}
