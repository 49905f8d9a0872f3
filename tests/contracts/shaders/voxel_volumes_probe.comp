#version 460
#extension GL_GOOGLE_include_directive : require
// The surface-plane offset of the voxel-volumes contract through the normal volume's w, as
// common.voxelize stores it and the voxel families read it back.
#include "contracts/voxel_volumes.glsl"

layout(local_size_x = 1) in;

layout(set = 0, binding = 0, std430) readonly buffer Offsets { float offsets[]; };
// Per offset: x the offset read back, y 1 when the voxel reads as occupied.
layout(set = 0, binding = 1, std430) writeonly buffer Decoded { vec2 decoded[]; };

layout(push_constant) uniform Push { uint count; } pc;

void main() {
  for (uint i = 0u; i < pc.count; ++i) {
    vec4 texel = vec4(0.0, 0.0, 1.0, voxel_encode_plane_offset(offsets[i]));
    decoded[i] = vec2(voxel_plane_offset(texel), voxel_normal_occupied(texel) ? 1.0 : 0.0);
  }
}
