#version 460
#extension GL_GOOGLE_include_directive : require
// Encodes surfaces as common.gbuffer does and decodes them as the readers do, both through the
// G-buffer contract: what comes back must be what went in, whichever channel a reader uses.
#include "contracts/gbuffer.glsl"

layout(local_size_x = 1) in;

struct Surface {
  vec4 base_color_metallic;
  vec4 normal_roughness;
  vec4 emission_occlusion;
};
layout(set = 0, binding = 0, std430) readonly buffer Surfaces { Surface surfaces[]; };
// Per surface: base colour + metallic, normal + roughness (from the normal target), emission +
// occlusion (from the material target), roughness from the material target, occlusion from the
// base-colour target, coverage, and whether a depth of 0.5 and one of 1.0 hold a surface.
layout(set = 0, binding = 1, std430) writeonly buffer Decoded { vec4 decoded[]; };

layout(push_constant) uniform Push { uint count; } pc;

void main() {
  for (uint i = 0u; i < pc.count; ++i) {
    Surface s = surfaces[i];
    GbufferTexels t = gbuffer_encode(s.base_color_metallic.rgb, s.normal_roughness.xyz,
                                     s.base_color_metallic.a, s.normal_roughness.w,
                                     s.emission_occlusion.a, s.emission_occlusion.rgb);
    decoded[4u * i + 0u] = vec4(gbuffer_base_color(t.base_color), gbuffer_metallic(t.material));
    decoded[4u * i + 1u] = vec4(gbuffer_normal(t.normal), gbuffer_roughness(t.normal));
    decoded[4u * i + 2u] = vec4(gbuffer_emission(t.emission), gbuffer_occlusion(t.material));
    decoded[4u * i + 3u] = vec4(t.material.g, t.base_color.a, t.material.a,
                                (gbuffer_has_surface(0.5) ? 1.0 : 0.0) +
                                    (gbuffer_has_surface(1.0) ? 2.0 : 0.0));
  }
}
