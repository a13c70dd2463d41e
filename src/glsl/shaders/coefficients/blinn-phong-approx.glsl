// Akenine-Moller, Haines & Hoffman, "Real-Time Rendering" (docs/math.md 2 `blinn-phong-approx`): k = (n + 8)/(8 pi), 2-8 % high.
#include "common/pi.glsl"
float specula_blinn_phong_approx_coef(float n) {
  return (n + 8.0) / (8.0 * SPECULA_PI);
}
