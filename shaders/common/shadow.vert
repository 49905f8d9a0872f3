#version 460
#extension GL_GOOGLE_include_directive : require
#include "lib/scene.glsl"

// Relative to the shadow's origin, so that scenes far from the world origin keep precision.
layout(push_constant) uniform Push {
  mat4 view_proj;
  vec4 origin;
} pc;

layout(location = 0) in vec3 in_position;

void main() {
  vec4 world = scene_instances[gl_InstanceIndex].world * vec4(in_position, 1.0);
  gl_Position = pc.view_proj * vec4(world.xyz - pc.origin.xyz, 1.0);
}
