#version 460
#extension GL_GOOGLE_include_directive : require
// Reads records of the shadow-data contract as the GLSL twin lays them out and writes every
// field back as a flat list of floats, in declaration order.
#include "contracts/shadow_data.glsl"

layout(local_size_x = 1) in;

layout(set = 0, binding = 0, std430) readonly buffer Lights { ShadowLight lights[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Fields { float fields[]; };

layout(push_constant) uniform Push { uint light_count; } pc;

void main() {
  uint o = 0u;
  for (uint l = 0u; l < pc.light_count; ++l) {
    for (int face = 0; face < 6; ++face) {
      for (int column = 0; column < 4; ++column) {
        for (int row = 0; row < 4; ++row) fields[o++] = lights[l].view_proj[face][column][row];
      }
    }
    for (int i = 0; i < 4; ++i) fields[o++] = lights[l].origin[i];
    for (int i = 0; i < 4; ++i) fields[o++] = lights[l].info[i];
  }
}
