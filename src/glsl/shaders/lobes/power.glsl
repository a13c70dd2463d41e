// Phong 1975, "Illumination for Computer Generated Pictures" (docs/math.md 2 `phong`, `blinn-phong`): F = c^n.
float specula_power_lobe(float c, float n) {
  return c > 0.0 ? pow(min(c, 1.0), n) : 0.0;
}
