#version 460
#extension GL_GOOGLE_include_directive : require
// direct + (indirect diffuse + indirect specular) * ambient occlusion * scale; optionally also
// the indirect term alone, exactly as added.
#include "lib/common.glsl"

#ifndef HAS_DIFFUSE
#define HAS_DIFFUSE 0
#endif
#ifndef HAS_SPECULAR
#define HAS_SPECULAR 0
#endif
#ifndef HAS_AO
#define HAS_AO 0
#endif
#ifndef HAS_INDIRECT_OUT
#define HAS_INDIRECT_OUT 0
#endif

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D in_direct;
#if HAS_DIFFUSE
layout(set = 0, binding = 1) uniform sampler2D in_diffuse;
#endif
#if HAS_SPECULAR
layout(set = 0, binding = 2) uniform sampler2D in_specular;
#endif
#if HAS_AO
layout(set = 0, binding = 3) uniform sampler2D in_ao;
#endif
layout(set = 0, binding = 4) writeonly uniform image2D out_radiance;
#if HAS_INDIRECT_OUT
layout(set = 0, binding = 5) writeonly uniform image2D out_indirect;
#endif

layout(push_constant) uniform Push {
  uvec2 size;
  float indirect_scale;
  float pad;
} pc;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  vec3 indirect = vec3(0.0);
#if HAS_DIFFUSE
  indirect += texelFetch(in_diffuse, p, 0).rgb;
#endif
#if HAS_SPECULAR
  indirect += texelFetch(in_specular, p, 0).rgb;
#endif
#if HAS_AO
  indirect *= clamp(texelFetch(in_ao, p, 0).r, 0.0, 1.0);
#endif
  indirect *= pc.indirect_scale;
  vec3 result = texelFetch(in_direct, p, 0).rgb + indirect;
  imageStore(out_radiance, p, vec4(sanitize_radiance(result), 1.0));
#if HAS_INDIRECT_OUT
  imageStore(out_indirect, p, vec4(sanitize_radiance(indirect), 1.0));
#endif
}
