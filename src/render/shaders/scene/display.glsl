// Narkowicz 2016, "ACES Filmic Tone Mapping Curve", and IEC 61966-2-1 (sRGB): the display transform of render/image.h, in the shader.
// Narkowicz 2016, "ACES Filmic Tone Mapping Curve" (render/image.h aces_narkowicz): x(2.51x + 0.03)/(x(2.43x + 0.59) + 0.14), clamped to [0, 1].
vec3 scene_aces(vec3 x) {
  return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

// IEC 61966-2-1, the sRGB transfer curve (render/image.h srgb_encode): 12.92 L for L <= 0.0031308, else 1.055 L^(1/2.4) - 0.055.
vec3 scene_srgb_encode(vec3 l) {
  return mix(1.055 * pow(l, vec3(1.0 / 2.4)) - 0.055, 12.92 * l, lessThanEqual(l, vec3(0.0031308)));
}

// render/image.h Display and to_srgb8 before the rounding: radiance 2^exposure, tone-mapped (u_tone_map 1: ACES), clamped to [0, 1], sRGB-encoded.
vec3 scene_display(vec3 radiance) {
  vec3 x = radiance * exp2(u_exposure);
  if (u_tone_map == 1) x = scene_aces(x);
  return scene_srgb_encode(clamp(x, 0.0, 1.0));
}
