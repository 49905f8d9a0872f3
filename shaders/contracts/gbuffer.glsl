#ifndef VOXGI_GBUFFER_GLSL
#define VOXGI_GBUFFER_GLSL
// Contract: the G-buffer common.gbuffer writes and the screen-space passes of every family
// read. C++ twin: passes/contracts/gbuffer.hpp (slot names and formats). No bindings: readers
// declare the targets they need at their own bindings and decode the fetched texels here.
//
//   base_color  rgba8 sRGB or rgba16f: rgb linear base colour, a occlusion
//   normal      rgba16f or rgba32f:    xyz world-space shading normal, w perceptual roughness
//   material    rgba8 unorm or rgba16f: r metallic, g roughness, b occlusion, a coverage (1)
//   emission    rgba16f or rgba32f:    rgb emitted radiance (sanitized), a 1
//   depth       d32 float:             Vulkan clip-space depth, cleared to 1 where nothing was
//                                      drawn
// Positions are not stored: reconstruct_world_position (lib/common.glsl) rebuilds them from
// the depth and the frame's inverse projection and view.

#include "lib/common.glsl"

struct GbufferTexels {
  vec4 base_color;
  vec4 normal;
  vec4 material;
  vec4 emission;
};

GbufferTexels gbuffer_encode(vec3 base_color, vec3 normal, float metallic, float roughness,
                             float occlusion, vec3 emission) {
  GbufferTexels t;
  t.base_color = vec4(base_color, occlusion);
  t.normal = vec4(normal, roughness);
  t.material = vec4(metallic, roughness, occlusion, 1.0);
  t.emission = vec4(emission, 1.0);
  return t;
}

// False where no geometry was drawn.
bool gbuffer_has_surface(float depth) { return depth < 1.0 && !isnan(depth); }

vec3 gbuffer_base_color(vec4 base_color_texel) {
  return clamp(base_color_texel.rgb, vec3(0.0), vec3(1.0));
}
// A unit normal; up where the stored one is degenerate.
vec3 gbuffer_normal(vec4 normal_texel) {
  return safe_normalize(normal_texel.xyz, vec3(0.0, 1.0, 0.0));
}
float gbuffer_roughness(vec4 normal_texel) { return clamp(normal_texel.w, 0.0, 1.0); }
float gbuffer_metallic(vec4 material_texel) { return clamp(material_texel.r, 0.0, 1.0); }
float gbuffer_occlusion(vec4 material_texel) { return clamp(material_texel.b, 0.0, 1.0); }
vec3 gbuffer_emission(vec4 emission_texel) { return emission_texel.rgb; }

#endif
