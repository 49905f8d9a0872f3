#version 460
#extension GL_GOOGLE_include_directive : require
// Constant ambient: diffuse reflection c_diff * L * occlusion of a uniform environment L.
#include "lib/common.glsl"
#include "contracts/gbuffer.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform sampler2D g_base_color;
layout(set = 0, binding = 1) uniform sampler2D g_material;
layout(set = 0, binding = 2) uniform sampler2D g_depth;
layout(set = 0, binding = 3) writeonly uniform image2D out_radiance;

layout(push_constant) uniform Push {
  uvec2 size;
  float radiance;
  float pad;
} pc;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(p), pc.size))) return;
  vec3 result = vec3(0.0);
  if (gbuffer_has_surface(texelFetch(g_depth, p, 0).r)) {
    vec4 material = texelFetch(g_material, p, 0);
    float metallic = gbuffer_metallic(material);
    float occlusion = gbuffer_occlusion(material);
    vec3 c_diff = gbuffer_base_color(texelFetch(g_base_color, p, 0)) * (1.0 - metallic);
    result = c_diff * pc.radiance * occlusion;
  }
  imageStore(out_radiance, p, vec4(sanitize_radiance(result), 1.0));
}
