#version 460
#extension GL_GOOGLE_include_directive : require
// Depth- and normal-aware upsampling of the half-resolution cone-tracing scratch (rgb result,
// a = AO visibility) to full resolution: the four nearest half-resolution samples, each at
// the G-buffer pixel it was traced from, weighted bilinearly x depth similarity x normal
// similarity; where all four belong to other surfaces the closest in depth is taken. The
// diffuse scratch holds E / pi (trace.comp), multiplied here by each pixel's own c_diff.
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "vct/gbuffer_sample.glsl"

#ifndef HAS_AO
#define HAS_AO 0
#endif
#ifndef SPECULAR
#define SPECULAR 0
#endif
#ifndef AO_FORMAT
#define AO_FORMAT r16f
#endif

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 7, rgba16f) writeonly uniform image2D out_result;
#if HAS_AO
layout(set = 0, binding = 8, AO_FORMAT) writeonly uniform image2D out_ao;
#endif
layout(set = 0, binding = 9) uniform sampler2D half_scratch;

layout(push_constant) uniform Push {
  uvec2 size;  // full resolution
  float depth_tolerance;  // relative view-depth difference with weight 1/2
  float normal_power;
} pc;

void store(ivec2 pixel, vec4 value) {
  imageStore(out_result, pixel, vec4(sanitize_radiance(value.rgb), 1.0));
#if HAS_AO
  imageStore(out_ao, pixel, vec4(clamp(value.a, 0.0, 1.0)));
#endif
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.size))) return;
  GbufferSample g = gbuffer_sample(pixel);
  if (!g.valid) {
    store(pixel, vec4(0.0, 0.0, 0.0, 1.0));
    return;
  }
  ivec2 half_size = textureSize(half_scratch, 0);
  vec2 h = (vec2(pixel) + 0.5) * 0.5 - 0.5;
  ivec2 base = ivec2(floor(h));
  vec2 f = h - vec2(base);
  vec4 sum = vec4(0.0);
  float weight_sum = 0.0;
  vec4 closest = vec4(0.0, 0.0, 0.0, 1.0);
  float closest_difference = 1e30;
  for (int i = 0; i < 4; ++i) {
    ivec2 offset = ivec2(i & 1, i >> 1);
    ivec2 tap = clamp(base + offset, ivec2(0), half_size - 1);
    GbufferSample t = gbuffer_sample(gbuffer_block_representative(tap));
    vec4 value = texelFetch(half_scratch, tap, 0);
    if (!t.valid) continue;
    float bilinear = (offset.x == 1 ? f.x : 1.0 - f.x) * (offset.y == 1 ? f.y : 1.0 - f.y);
    float difference = abs(t.view_depth - g.view_depth) / max(g.view_depth, 1e-6);
    float relative = difference / pc.depth_tolerance;
    float depth_weight = 1.0 / (1.0 + relative * relative);
    float normal_weight = pow(clamp(dot(t.normal, g.normal), 0.0, 1.0), pc.normal_power);
    float w = max(bilinear, 1e-3) * depth_weight * normal_weight;
    sum += w * value;
    weight_sum += w;
    if (difference < closest_difference) {
      closest_difference = difference;
      closest = value;
    }
  }
  vec4 value = weight_sum > 1e-4 ? sum / weight_sum : closest;
#if !SPECULAR
  value.rgb *= gbuffer_diffuse_reflectance(g);
#endif
  store(pixel, value);
}
