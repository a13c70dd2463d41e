// Romanyuk et al. 2023, "The Development of Physically Correct Reflectance Model Based on Logarithm Function", F_log (docs/math.md 2 `log`): F = max(0, 1 - log2(1 - n log2 c)/2), 0 for c <= 2^(-3/n).
float specula_log_lobe(float c, float n) {
  if (c <= 0.0) return 0.0;
  return max(1.0 - 0.5 * log2(1.0 - n * log2(min(c, 1.0))), 0.0);
}
