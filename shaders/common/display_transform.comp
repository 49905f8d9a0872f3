#version 460
#extension GL_GOOGLE_include_directive : require
// Scene-linear radiance → display-referred sRGB through the baked OCIO LUT.
#include "lib/display_lut.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D in_radiance;
layout(set = 0, binding = 1) uniform sampler3D display_lut;
layout(set = 0, binding = 2) writeonly uniform image2D out_display;

layout(push_constant) uniform Push {
  uvec2 size;
  float exposure_scale;
  float shaper_min_log2;
  float shaper_max_log2;
} pc;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  vec3 linear = texelFetch(in_radiance, p, 0).rgb * pc.exposure_scale;
  vec3 display = apply_display_lut(display_lut, linear,
                                   vec2(pc.shaper_min_log2, pc.shaper_max_log2));
  imageStore(out_display, p, vec4(clamp(display, 0.0, 1.0), 1.0));
}
