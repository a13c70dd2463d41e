// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", its lobe in the rv form, exact (docs/math.md 2): k = 1/(2 pi I), I = n^2 ln n/(n-1)^3 - n/(n-1)^2 - 1/(2(n-1)),
// or I = sum_j (1-n)^j 2/((j+1)(j+2)(j+3)) where that form cancels (|1 - n| <= 1/2; 24 terms reach float precision).
#include "common/pi.glsl"
float specula_schlick_rv_coef(float n) {
  float m = 1.0 - n;
  float integral = 0.0;
  if (abs(m) <= 0.5) {
    float power = 1.0;
    for (int j = 0; j < 24; ++j) {
      float k = float(j);
      integral += power * 2.0 / ((k + 1.0) * (k + 2.0) * (k + 3.0));
      power *= m;
    }
  } else {
    float d = n - 1.0;
    float r = n / d;
    integral = (r * r * log(n) - r - 0.5) / d;
  }
  return 1.0 / (2.0 * SPECULA_PI * integral);
}
