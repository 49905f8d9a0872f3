#version 460
#extension GL_GOOGLE_include_directive : require
#include "lib/common.glsl"
#include "lib/scene.glsl"
#include "contracts/gbuffer.glsl"

layout(location = 0) in vec3 in_normal;
layout(location = 1) in vec4 in_tangent;
layout(location = 2) in vec2 in_uv;
layout(location = 3) flat in uint in_material;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;

layout(location = 0) out vec4 out_base_color;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_material;
layout(location = 3) out vec4 out_emission;

void main() {
  // Back faces of double-sided materials are shaded with the normal facing the viewer.
  vec3 normal = gl_FrontFacing ? in_normal : -in_normal;
  vec4 tangent = vec4(gl_FrontFacing ? in_tangent.xyz : -in_tangent.xyz, in_tangent.w);
  MaterialSample m =
      sample_material(in_material, SurfaceAttributes(in_uv, in_uv1, in_color), normal, tangent);
  if (m.alpha_mask && m.base_color.a < m.alpha_cutoff) discard;
  GbufferTexels g = gbuffer_encode(m.base_color.rgb, m.normal, m.metallic, m.roughness,
                                   m.occlusion, sanitize_radiance(m.emissive));
  out_base_color = g.base_color;
  out_normal = g.normal;
  out_material = g.material;
  out_emission = g.emission;
}
