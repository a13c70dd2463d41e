// Romanyuk et al. 2023, "The Development of Physically Correct Reflectance Model Based on Logarithm Function", its Gauss lobe (docs/math.md 2 `gauss`): F = exp(-n theta^2/2), theta = acos c.
float specula_gauss_lobe(float c, float n) {
  float theta = acos(clamp(c, -1.0, 1.0));
  return c > 0.0 ? exp(-0.5 * n * theta * theta) : 0.0;
}
