#ifndef VOXGI_DISPLAY_LUT_GLSL
#define VOXGI_DISPLAY_LUT_GLSL
// Scene-linear → display code values through a LUT baked by voxgi::color::DisplayTransform.
// Exactly DisplayTransform::apply_lut: the shaper below, then trilinear filtering between
// texel centres (the sampler must be linear, clamp-to-edge, no mips).

// Linear value → LUT coordinate in [0, 1]: linear from 0 to 2^min over the first texel step
// (black stays black), log2 from 2^min to 2^max over the rest.
float display_lut_shaper(float linear, vec2 shaper_range, float size) {
  float x = linear > 0.0 ? linear : 0.0;  // also NaN → 0
  float d = 1.0 / (size - 1.0);
  float lo = exp2(shaper_range.x);
  float t = x < lo ? d * x / lo
                   : d + (1.0 - d) * (log2(x) - shaper_range.x) / (shaper_range.y - shaper_range.x);
  return min(t, 1.0);
}

vec3 apply_display_lut(sampler3D lut, vec3 linear, vec2 shaper_range) {
  float size = float(textureSize(lut, 0).x);
  vec3 t = vec3(display_lut_shaper(linear.r, shaper_range, size),
                display_lut_shaper(linear.g, shaper_range, size),
                display_lut_shaper(linear.b, shaper_range, size));
  vec3 coord = t * ((size - 1.0) / size) + 0.5 / size;
  return textureLod(lut, coord, 0.0).rgb;
}

#endif
