// Blinn 1977, "Models of Light Reflection for Computer Synthesized Pictures" (docs/math.md 1, form nh): c = N.H, H = (L + V)/|L + V|.
float specula_cos_nh(vec3 N, vec3 L, vec3 V) {
  vec3 h = L + V;
  float len2 = dot(h, h);
  return len2 > 0.0 ? dot(N, h) * inversesqrt(len2) : 0.0;
}
