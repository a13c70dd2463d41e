// Phong 1975, "Illumination for Computer Generated Pictures" (docs/math.md 1, form rv): c = R.V, R = 2(N.L)N - L the mirror direction of L.
float specula_cos_rv(vec3 N, vec3 L, vec3 V) {
  return dot(2.0 * dot(N, L) * N - L, V);
}
