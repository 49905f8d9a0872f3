#version 460
#extension GL_GOOGLE_include_directive : require
// lpv.downsample: the injected LPV and the geometry volume on every octree level (seed 002
// sec. 4.2; docs/lpv.md).
//
// MODE 0: octree level 0: decodes lpv.inject's fixed-point sums (the seed's LPVInject result)
//         and builds the geometry volume from the voxels (GVInject); marks the index where
//         light was injected.
// MODE 1: octree level `level` from level - 1 (LPVDownsample, GVDownsample, eq. 11): the SH is
//         the mean of the 8 children, so every level holds intensity per level-0 cell volume
//         (a coarse cell's flux is 8^level times its value). The geometry is the children's
//         surface over the coarse cell: a surface of area a in a cell of side s stops a / s^2 of
//         the light crossing it, so opacity = min(1, 2 x mean child opacity) and the mean
//         normal is 2 x the mean of opacity x normal over that opacity (a wall one child thick
//         stays a wall; the seed's plain mean would let half the light through it).
#include "lib/common.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#include "contracts/voxel_volumes.glsl"
#include "lpv/cells.glsl"

#ifndef HAS_OCCLUSION
#define HAS_OCCLUSION 0
#endif

layout(local_size_x = 64) in;

layout(set = 0, binding = 1, std430) readonly buffer Injected {
  uint max_magnitude_bits;
  uint contributions;
  uint pad0;
  uint pad1;
  int coefficients[];
} injected;
// A record per cell of every octree level (lpv/cells.glsl).
layout(set = 0, binding = 2, std430) buffer Levels { vec4 levels[]; };
#if HAS_OCCLUSION
layout(set = 0, binding = 3) uniform sampler3D voxel_albedo;
layout(set = 0, binding = 4) uniform sampler3D voxel_normal;
#endif

layout(push_constant) uniform Push {
  uint mode;
  uint level;  // MODE 1: the octree level written
  uint pad0;
  uint pad1;
} pc;

#if HAS_OCCLUSION
// The geometry of a voxel: its mean normal m (|m| <= 1; ~0 where opposite faces share the
// voxel) and its opacity.
vec4 voxel_geometry(ivec3 c, int cascade) {
  if (!voxel_level_valid(cascade)) return vec4(0.0);
  ivec3 t = voxel_texel(c, cascade);
  vec4 n = texelFetch(voxel_normal, t, 0);
  float opacity = clamp(texelFetch(voxel_albedo, t, 0).a, 0.0, 1.0);
  if (!voxel_normal_occupied(n) || !(opacity > 0.0)) return vec4(0.0);
  vec3 m = n.xyz;
  float len = length(m);
  if (!(len <= 1.0)) m = len > 1.0 ? m / len : vec3(0.0);
  return vec4(m, opacity);
}
#endif

bool has_light(vec4 sh[3]) {
  return any(notEqual(sh[0], vec4(0.0))) || any(notEqual(sh[1], vec4(0.0))) ||
         any(notEqual(sh[2], vec4(0.0)));
}

void write_record(int cell, vec4 sh[3], vec4 geometry, int level) {
  int at = cell * LPV_RECORD_VEC4S;
  for (int ch = 0; ch < 3; ++ch) levels[at + ch] = sh[ch];
  levels[at + 3] = vec4(0.0, 0.0, 0.0, has_light(sh) ? float(level) : -1.0);
  levels[at + 4] = geometry;
}

void main() {
  int index = int(gl_GlobalInvocationID.x);
  if (pc.mode == 0u) {
    LpvOctreeCell cell = lpv_octree_coords(index, 1);
    if (cell.level != 0) return;
    float scale = lpv_fixed_point_scale(injected.max_magnitude_bits, injected.contributions);
    vec4 sh[3];
    for (int ch = 0; ch < 3; ++ch) {
      sh[ch] = vec4(0.0);
      if (scale > 0.0) {
        int base = index * 12 + ch * 4;
        sh[ch] = vec4(injected.coefficients[base], injected.coefficients[base + 1],
                      injected.coefficients[base + 2], injected.coefficients[base + 3]) / scale;
      }
    }
    vec4 geometry = vec4(0.0);
#if HAS_OCCLUSION
    geometry = voxel_geometry(cell.c, lpv_cascade_level(cell.cascade));
#endif
    write_record(index, sh, geometry, 0);
    return;
  }

  int level = int(pc.level);
  int n = lpv_level_resolution(level);
  int count = n * n * n * lpv_cascade_count();
  if (index >= count) return;
  int i = index;
  ivec3 c = ivec3(i % n, (i / n) % n, (i / (n * n)) % n);
  int cascade = i / (n * n * n);
  vec4 sh[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
  float opacity = 0.0;
  vec3 oriented = vec3(0.0);
  for (int k = 0; k < 8; ++k) {
    ivec3 child = 2 * c + ivec3(k & 1, (k >> 1) & 1, k >> 2);
    int at = lpv_octree_cell(child, cascade, level - 1) * LPV_RECORD_VEC4S;
    for (int ch = 0; ch < 3; ++ch) sh[ch] += levels[at + ch];
    vec4 g = levels[at + 4];
    opacity += g.w;
    oriented += g.w * g.xyz;
  }
  for (int ch = 0; ch < 3; ++ch) sh[ch] *= 0.125;
  vec4 geometry = vec4(0.0);
  float coarse_opacity = min(1.0, 0.25 * opacity);
  if (coarse_opacity > 0.0) {
    vec3 m = 0.25 * oriented / coarse_opacity;
    float len = length(m);
    if (len > 1.0) m /= len;
    geometry = vec4(m, coarse_opacity);
  }
  write_record(lpv_level_base(level) + index, sh, geometry, level);
}
