#version 460
#extension GL_GOOGLE_include_directive : require
#include "lib/scene.glsl"

layout(push_constant) uniform Push { mat4 view_proj; } pc;

layout(location = 0) in vec3 in_position;

void main() {
  gl_Position = pc.view_proj * (scene_instances[gl_InstanceIndex].world * vec4(in_position, 1.0));
}
