// Lafortune & Willems 1994, "Using the Modified Phong Reflectance Model for Physically Based Rendering" (docs/math.md 2 `phong-lafortune`): k = (n + 1)/(2 pi), without the cos term.
#include "common/pi.glsl"
float specula_phong_lafortune_coef(float n) {
  return (n + 1.0) / (2.0 * SPECULA_PI);
}
