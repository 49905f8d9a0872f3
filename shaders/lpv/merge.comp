#version 460
#extension GL_GOOGLE_include_directive : require
// lpv.merge: the octree levels into one record per level-0 cell for the lookup (seed 002 sec.
// 4.2, LPVMerge; docs/lpv.md). Level o holds intensity per level-0 cell volume: a coarse
// cell's flux is 8^o times its value and its cross-section 4^o level-0 cells, so in level-0
// units its irradiance is 2^o times its value (SH and stopped flux alike). The stopped flux is
// per the cell's surface (opacity x cross-section): level o's stopped flux becomes the
// irradiance it gives, spread over the level-0 cell's own surface.
//
// MODE 0 (index, eq. 10): the cell takes the finest level o whose cell c >> o holds light
//         (the index volume I = min_o I_o), the last level where none does.
// MODE 1 (shells): the sum over the levels, each of which accumulated only the distances it
//         resolves (lpv/propagate.comp).
// With one level both copy level 0.
#include "lib/common.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#include "lpv/cells.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 1, std430) readonly buffer Levels { vec4 levels[]; };
layout(set = 0, binding = 2, std430) writeonly buffer Merged { vec4 merged[]; };

layout(push_constant) uniform Push {
  uint mode;
  uint octree_levels;
  uint pad0;
  uint pad1;
} pc;

void main() {
  int index = int(gl_GlobalInvocationID.x);
  LpvOctreeCell cell = lpv_octree_coords(index, 1);
  if (cell.level != 0) return;
  int fine = index * LPV_RECORD_VEC4S;
  vec4 geometry = levels[fine + 4];
  int last = int(pc.octree_levels) - 1;

  int chosen = last;
  for (int o = 0; o <= last; ++o) {
    int at = lpv_octree_cell(cell.c >> o, cell.cascade, o) * LPV_RECORD_VEC4S;
    if (levels[at + 3].w >= 0.0) {
      chosen = o;
      break;
    }
  }
  int first = pc.mode == 0u ? chosen : 0;
  int end = pc.mode == 0u ? chosen : last;
  vec4 sh[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
  vec3 stopped = vec3(0.0);
  for (int o = first; o <= end; ++o) {
    int at = lpv_octree_cell(cell.c >> o, cell.cascade, o) * LPV_RECORD_VEC4S;
    float to_fine = float(1 << o);
    for (int ch = 0; ch < 3; ++ch) sh[ch] += to_fine * levels[at + ch];
    float opacity = levels[at + 4].w;
    if (opacity > 0.0) stopped += to_fine * levels[at + 3].rgb * (geometry.w / opacity);
  }
  for (int ch = 0; ch < 3; ++ch) merged[fine + ch] = sh[ch];
  merged[fine + 3] = vec4(stopped, float(chosen));
  merged[fine + 4] = geometry;
}
