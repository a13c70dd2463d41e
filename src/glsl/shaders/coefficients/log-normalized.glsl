// Romanyuk et al. 2023, "The Development of Physically Correct Reflectance Model Based on Logarithm Function", its coef(n) exact (docs/math.md 4), in float.
${log_coef_j_series}
${log_coef_k_series}
// docs/math.md 4 (Romanyuk et al. 2023, exact): coef(n) = 1/(pi a J(a)), a = 2 ln2/n; J (n >= 1) and K = a J (n < 1)
// by Chebyshev series: 4e-7 relative in float for n in (0, 1e30] (normalize::log_rv_approx, same arithmetic).
float specula_log_rv_coef(float n) {
  if (n >= 1.0) return n * ${1/(2 pi ln2)} / specula_log_coef_j(${2 ln2} / n);
  return ${1/pi} / specula_log_coef_k(n * ${1/(2 ln2)});
}
