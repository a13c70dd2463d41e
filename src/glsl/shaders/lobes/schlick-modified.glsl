// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", second degree (docs/math.md 2 `schlick-modified`, reconstructed): F = (s c)^2/(n - n c + s c)^2.
float specula_schlick_modified_lobe(float c, float n, float s) {
  c = clamp(c, 0.0, 1.0);
  float q = s * c / (n * (1.0 - c) + s * c);
  return q * q;
}
