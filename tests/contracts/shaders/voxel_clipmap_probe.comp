#version 460
#extension GL_GOOGLE_include_directive : require
// Reads the clipmap-info buffer through the voxel-clipmap contract's GLSL declaration and
// accessors and writes every field back as a flat list of floats, in declaration order.
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"

layout(local_size_x = 1) in;

layout(set = 0, binding = 1, std430) writeonly buffer Fields { float fields[]; };

void main() {
  uint o = 0u;
  for (int i = 0; i < 4; ++i) fields[o++] = voxel_clipmap.anchor[i];
  fields[o++] = float(voxel_resolution());
  fields[o++] = float(voxel_level_count());
  fields[o++] = float(voxel_clipmap.dims.z);
  fields[o++] = float(voxel_clipmap.dims.w);
  for (int level = 0; level < VOXEL_CLIPMAP_MAX_LEVELS; ++level) {
    for (int i = 0; i < 3; ++i) fields[o++] = float(voxel_clipmap.levels[level].origin_voxel[i]);
    fields[o++] = voxel_level_valid(level) ? 1.0 : 0.0;
    for (int i = 0; i < 3; ++i) fields[o++] = voxel_level_min(level)[i];
    fields[o++] = voxel_size(level);
  }
}
