#version 460
// Zeroes the first `words` words of the voxelization scratch buffer.

#include "common/voxel_accumulate.glsl"

layout(local_size_x = 64) in;

layout(push_constant) uniform VoxelClearPush {
  uint words;
} clear_range;

void main() {
  uint stride = gl_NumWorkGroups.x * 64u;
  for (uint i = gl_GlobalInvocationID.x; i < clear_range.words; i += stride) voxel_scratch[i] = 0u;
}
