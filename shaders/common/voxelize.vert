#version 460
// Voxelization: scene vertices to window coordinates of the level being voxelized.

#include "lib/scene.glsl"
#include "common/voxel_draw.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 3) in vec2 in_uv;
layout(location = 4) in vec2 in_uv1;
layout(location = 5) in vec4 in_color;

layout(location = 0) out vec3 out_window;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) flat out uint out_instance;
layout(location = 4) out vec3 out_anchored;
layout(location = 5) out vec2 out_uv1;
layout(location = 6) out vec4 out_color;

void main() {
  SceneInstance instance = scene_instances[gl_InstanceIndex];
  // Translation minus anchor first: both are large for scenes far from the origin, their
  // difference is exact, and the rest of the arithmetic stays small.
  vec3 relative =
      mat3(instance.world) * in_position + (instance.world[3].xyz - voxel_draw.anchor.xyz);
  out_window = (relative - voxel_draw.level_min_size.xyz) / voxel_draw.level_min_size.w;
  out_anchored = relative / voxel_draw.level_min_size.w;
  out_normal = mat3(instance.normal_matrix) * in_normal;
  out_uv = in_uv;
  out_uv1 = in_uv1;
  out_color = in_color;
  out_instance = uint(gl_InstanceIndex);
  gl_Position = vec4(0.0, 0.0, 0.5, 1.0);
}
