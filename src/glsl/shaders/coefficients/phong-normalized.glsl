// Lewis 1994, "Making Shaders More Physically Plausible" (docs/math.md 2 `phong-normalized`): k = (n + 2)/(2 pi), exact for the rv form.
#include "common/pi.glsl"
float specula_phong_rv_coef(float n) {
  return (n + 2.0) / (2.0 * SPECULA_PI);
}
