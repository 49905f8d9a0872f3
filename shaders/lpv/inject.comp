#version 460
#extension GL_GOOGLE_include_directive : require
// lpv.inject: virtual point lights into the LPV cells (seed 002 sec. 3.2.2; docs/lpv.md).
// Each reflective-shadow-map texel, taken every `stride` texels, is a Lambertian emitter of
// flux Phi = stride^2 x its texel's flux (the injected texel stands for stride^2 texels: the
// solid angle is that of the injected resolution), radiant intensity (Phi / pi) max(0, n.w),
// placed half a cell along its normal, into the cell that holds it on every level whose window
// contains it (and into that level's "outer" volume when the next finer window does not,
// lpv/cells.glsl). Emissive voxels inject the flux of the emitter in their column, pi x L_e x
// (voxel edge)^2 / |n_a|, from the frontmost voxel of the column, on their own level (see
// emission_vpl). Sums are fixed point (shaders/lpv/cells.glsl), so the result does not depend
// on the order threads run in.
//
// MODE 0: clears the buffer and writes the header's contribution count.
// MODE 1: the largest coefficient magnitude of any contribution (atomicMax on float bits,
//         which order non-negative floats).
// MODE 2: the RSM texels.  MODE 3: the emissive voxels.
#include "lib/common.glsl"
#include "lpv/sh.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#include "contracts/voxel_volumes.glsl"
#include "lpv/cells.glsl"

layout(local_size_x = 64) in;

layout(set = 0, binding = 1) uniform sampler2DArray rsm_flux;
layout(set = 0, binding = 2) uniform sampler2DArray rsm_normal;
layout(set = 0, binding = 3) uniform sampler2DArray rsm_position;
layout(set = 0, binding = 4, std430) buffer Injected {
  uint max_magnitude_bits;
  uint contributions;
  uint pad0;
  uint pad1;
  int coefficients[];
} injected;
#if HAS_EMISSION
layout(set = 0, binding = 5) uniform sampler3D voxel_normal;
layout(set = 0, binding = 6) uniform sampler3D voxel_emission;
#endif

layout(push_constant) uniform Push {
  uint mode;
  uint stride;         // RSM texels between injected ones
  uint injected_edge;  // RSM edge / stride
  uint layers;         // RSM layers
  uint contributions;  // upper bound on the contributions to one coefficient
  uint words;          // the buffer's coefficient count (cells x 12)
  float normal_offset; // cells
  uint pad;
} pc;

struct Vpl {
  vec3 position;  // anchor-relative
  vec3 normal;
  vec3 flux;
  bool valid;
};

Vpl rsm_vpl(uint index) {
  uint e = pc.injected_edge;
  uint layer = index / (e * e);
  uint i = index % (e * e);
  ivec3 texel = ivec3(ivec2(i % e, i / e) * int(pc.stride) + int(pc.stride / 2u), int(layer));
  Vpl v;
  vec4 p = texelFetch(rsm_position, texel, 0);
  v.valid = layer < pc.layers && p.w > 0.5;
  v.position = voxel_relative(p.xyz);
  v.normal = safe_normalize(texelFetch(rsm_normal, texel, 0).xyz, vec3(0.0, 1.0, 0.0));
  v.flux = max(texelFetch(rsm_flux, texel, 0).rgb, vec3(0.0)) * float(pc.stride * pc.stride);
  v.valid = v.valid && all(lessThan(v.flux, vec3(3.0e38))) && max(v.flux.r, max(v.flux.g, v.flux.b)) > 0.0;
  return v;
}

#if HAS_EMISSION
// The axis of n's largest component, as the voxelization chooses it (z, then x, then y).
int dominant_axis(vec3 n) {
  vec3 m = abs(n);
  return (m.z >= m.x && m.z >= m.y) ? 2 : (m.x >= m.y ? 0 : 1);
}

// The voxel at texel t emits from a surface whose normal has the same dominant axis a, on the
// same side (sign of its component `side`).
bool emits_towards(ivec3 t, int a, float side) {
  vec4 n = texelFetch(voxel_normal, t, 0);
  vec3 le = texelFetch(voxel_emission, t, 0).rgb;
  if (!voxel_normal_occupied(n) || !(max(le.r, max(le.g, le.b)) > 0.0)) return false;
  float len = length(n.xyz);
  if (!(len > 0.25)) return false;
  return dominant_axis(n.xyz) == a && n[a] * side > 0.0;
}

// An emissive voxel on its own level; position is its surface point.
Vpl emission_vpl(uint index, out int level) {
  // Over the voxels the first cascades are the clipmap's levels (lpv/cells.glsl).
  LpvOctreeCell cell = lpv_octree_coords(int(index), 1);
  level = cell.cascade;
  ivec3 c = cell.c;
  Vpl v;
  v.valid = false;
  if (level >= voxel_level_count() || !voxel_level_valid(level)) return v;
  ivec3 t = voxel_texel(c, level);
  vec4 n = texelFetch(voxel_normal, t, 0);
  vec3 le = max(texelFetch(voxel_emission, t, 0).rgb, vec3(0.0));
  float s = voxel_size(level);
  if (!voxel_normal_occupied(n) || max(le.r, max(le.g, le.b)) <= 0.0) return v;
  float len = length(n.xyz);
  // A voxel whose faces cancelled has no side to emit from; it is skipped.
  if (!(len > 0.25)) return v;
  v.normal = n.xyz / len;
  // The voxelization weighs emission by the part of the voxel's cross-section the emitter
  // covers along the dominant axis a of its normal, so every voxel of a column it crosses holds
  // that column's emission (two for a plane on the face between two layers, one or two for a
  // sloped one). The column's emitter has area s^2 / |n_a| per unit coverage: the frontmost
  // voxel of the column (the one the normal leaves through) injects it, the others nothing.
  int a = dominant_axis(v.normal);
  ivec3 front = c;
  front[a] += v.normal[a] > 0.0 ? 1 : -1;
  if (lpv_inside(front) && emits_towards(voxel_texel(front, level), a, v.normal[a])) return v;
  v.position = voxel_level_min(level) + (vec3(c) + 0.5 + voxel_plane_offset(n) * v.normal) * s;
  v.flux = SH_PI * le * s * s / abs(v.normal[a]);
  v.valid = true;
  return v;
}
#endif

float magnitude(Vpl v) { return max(v.flux.r, max(v.flux.g, v.flux.b)) / SH_PI * SH_COSINE_1; }

void add(int cell, Vpl v, float scale) {
  vec4 lobe = sh_clamped_cosine(v.normal) / SH_PI;
  for (int ch = 0; ch < 3; ++ch) {
    vec4 c = lobe * v.flux[ch] * scale;
    int base = cell * 12 + ch * 4;
    for (int k = 0; k < 4; ++k) {
      int q = int(round(c[k]));
      if (q != 0) atomicAdd(injected.coefficients[base + k], q);
    }
  }
}

// The cell of `level` a VPL goes into, `normal_offset` cells along its normal; false when the
// level's window does not hold it.
bool vpl_cell(Vpl v, int level, out ivec3 cell) {
  cell = ivec3(0);
  if (!voxel_level_valid(level)) return false;
  float s = voxel_size(level);
  cell = ivec3(floor(voxel_window_coord(v.position + v.normal * (pc.normal_offset * s), level)));
  return lpv_inside(cell);
}

// Into the "all" volume of every level in [first_level, last_level] whose window holds the
// VPL, and into the level's "outer" volume when the next finer window does not hold it
// (lpv/cells.glsl).
void inject(Vpl v, int first_level, int last_level) {
  float scale = lpv_fixed_point_scale(injected.max_magnitude_bits, injected.contributions);
  if (scale <= 0.0) return;
  for (int level = first_level; level <= last_level; ++level) {
    ivec3 cell;
    if (!vpl_cell(v, level, cell)) continue;
    add(lpv_cell(cell, level), v, scale);
    ivec3 finer;
    if (level > 0 && !vpl_cell(v, level - 1, finer)) {
      add(lpv_cell(cell, lpv_outer_cascade(level)), v, scale);
    }
  }
}

void main() {
  uint index = gl_GlobalInvocationID.x;
  if (pc.mode == 0u) {
    if (index < pc.words) injected.coefficients[index] = 0;
    if (index == 0u) {
      injected.max_magnitude_bits = 0u;
      injected.contributions = pc.contributions;
    }
    return;
  }
  // MODE 1 runs over the texels, then the voxels; MODE 2 the texels, MODE 3 the voxels.
  uint texels = pc.injected_edge * pc.injected_edge * pc.layers;
  uint first_voxel = pc.mode == 1u ? texels : 0u;
  bool from_rsm = pc.mode == 2u || (pc.mode == 1u && index < texels);
  Vpl v;
  int level = 0;
  if (from_rsm) {
    if (index >= texels) return;
    v = rsm_vpl(index);
  } else {
#if HAS_EMISSION
    uint voxel = index - first_voxel;
    if (voxel >= uint(lpv_voxel_total())) return;
    v = emission_vpl(voxel, level);
#else
    return;
#endif
  }
  if (!v.valid) return;
  if (pc.mode == 1u) {
    atomicMax(injected.max_magnitude_bits, floatBitsToUint(magnitude(v)));
  } else if (from_rsm) {
    inject(v, 0, voxel_level_count() - 1);
  } else {
    inject(v, level, level);
  }
}
