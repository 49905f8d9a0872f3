#version 460
#extension GL_GOOGLE_include_directive : require
// lpv.rsm: one face of a light's reflective shadow map (docs/lpv.md).
#include "lib/scene.glsl"
#include "lpv/rsm_push.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_tangent;
layout(location = 3) in vec2 in_uv;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec4 out_tangent;
layout(location = 3) out vec2 out_uv;
layout(location = 4) flat out uint out_material;
layout(location = 5) out vec2 out_uv1;
layout(location = 6) out vec4 out_color;

void main() {
  SceneInstance instance = scene_instances[gl_InstanceIndex];
  vec4 world = instance.world * vec4(in_position, 1.0);
  out_world = world.xyz;
  out_normal = mat3(instance.normal_matrix) * in_normal;
  out_tangent = scene_world_tangent(instance, in_tangent);
  out_uv = in_uv;
  out_uv1 = in_uv1;
  out_color = in_color;
  out_material = instance.material;
  gl_Position = pc.view_proj * vec4(world.xyz - pc.origin.xyz, 1.0);
}
