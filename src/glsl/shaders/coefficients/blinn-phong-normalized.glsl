// Giesen 2009, "Derivation of Phong and Blinn-Phong BRDF normalization factors" (docs/math.md 2 `blinn-phong-normalized`): k = (n+2)(n+4)/(8 pi (2^(-n/2) + n)), exact for nh.
#include "common/pi.glsl"
float specula_blinn_phong_nh_coef(float n) {
  return (n + 2.0) * (n + 4.0) / (8.0 * SPECULA_PI * (exp2(-0.5 * n) + n));
}
