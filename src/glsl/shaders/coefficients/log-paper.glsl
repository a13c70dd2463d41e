// Romanyuk et al. 2023, "The Development of Physically Correct Reflectance Model Based on Logarithm Function": its TuringBot fit as printed (docs/math.md 2 `log-paper`).
float specula_log_paper_coef(float n) {
  return 0.197 * (n + 1.24) + 0.068 / (0.64 + n);
}
