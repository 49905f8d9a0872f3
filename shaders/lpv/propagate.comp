#version 460
#extension GL_GOOGLE_include_directive : require
// lpv.propagate: the injected intensities spread cell to cell on every octree level (seed 002
// sec. 3.2.3 and 4.2; docs/lpv.md).
//
// MODE 0: copies lpv.downsample's injected levels into state 0 and the accumulation (S_0).
// MODE 1: step `step` of every level with cells in [cell_begin, ...): a cell B first counts
//         the flux its own geometry stops of what its current state sends (light that reaches
//         its surface); at its level's last step that is all. Otherwise B gathers from each
//         axial neighbour A the flux A's intensity sends through each of B's five faces that do
//         not face A, the exact integral of A's SH over the face as seen from A's centre
//         (lpv/sh.glsl), and re-emits it from its centre as a Lambertian lobe along the face's
//         normal: flux / pi x max(0, f.w). The 6 x 5 faces partition the sphere, so at factor 1
//         the total flux is carried, not created. Light crossing into B is multiplied by
//         1 - A's blocking towards the direction of travel; light that
//         leaves the window is lost. The accumulation adds each step: S = sum S_i.
//
// Octree levels propagate independently, each over its own cells. With the "shells" merge a
// level above 0 accumulates only the steps from `shell_start` on: level o's step t carries
// light about t 2^o level-0 cells, so level 0 counts distances up to k cells and level o the
// distances (k 2^(o-1), k 2^o]: every distance is counted once, at the coarsest resolution that
// still resolves it. The "index" merge (the seed's) accumulates every step on every level.
#include "lib/common.glsl"
#include "lpv/sh.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#include "lpv/cells.glsl"

#ifndef REPROJECT_DIRECTIONAL
#define REPROJECT_DIRECTIONAL 0
#endif

layout(local_size_x = 64) in;

// lpv.downsample's records per cell of every octree level (lpv/cells.glsl): the injected SH,
// the index mark and the geometry volume.
layout(set = 0, binding = 1, std430) readonly buffer InjectedLevels { vec4 injected[]; };
// States 0 and 1 (cells x 3 vec4 each).
layout(set = 0, binding = 2, std430) buffer Work { vec4 work[]; };
// The accumulated records per cell of every octree level.
layout(set = 0, binding = 3, std430) buffer Accumulated { vec4 accumulated[]; };

layout(push_constant) uniform Push {
  uint mode;
  uint src;         // state read by MODE 1
  uint step;        // MODE 1: the step, t in S_t
  int cell_begin;   // MODE 1: the first cell of this dispatch
  float factor;     // propagation factor (1: physical)
  uint shell_start; // first step levels above 0 accumulate
  uint octree_levels;
  int cell_total;    // cells of every octree level (one state's size)
  uvec4 iterations[2];  // per octree level: its number of steps
} pc;

int state_index(uint state, int cell, int ch) { return (int(state) * pc.cell_total + cell) * 3 + ch; }
uint level_iterations(int o) { return pc.iterations[o >> 2][o & 3]; }
bool accumulates(int o, uint step) { return o == 0 || step >= pc.shell_start; }


// Blocking potential (Kaplanyan and Dachsbacher 2010) of a voxel's geometry g for light
// travelling along unit w: the fraction of the rays crossing the cell that its surface stops,
// opacity x max(0, -m.w) for a surface of normal m filling the cell (one-sided: light leaving
// the surface passes); where opposite faces share the voxel (|m| < 1) the rest stops the
// average of |n.w| over directions, 1/2. Evaluated exactly, not from a two-band SH: that
// would stop 1/4 of the light running parallel to a wall in every cell and only 3/4 of the
// light hitting it head-on (docs/lpv.md).
float blocking(vec4 g, vec3 w) {
  float len = length(g.xyz);
  return g.w * (max(0.0, -dot(g.xyz, w)) + (1.0 - len) * 0.5);
}

const ivec3 AXES[6] = ivec3[6](ivec3(1, 0, 0), ivec3(-1, 0, 0), ivec3(0, 1, 0), ivec3(0, -1, 0),
                               ivec3(0, 0, 1), ivec3(0, 0, -1));

// The flux an intensity sh at a cell's centre sends through face f (normal f) of the neighbour
// along d: the exact integral over the face's solid angle (lpv/sh.glsl).
float face_flux(vec4 sh, ivec3 d, ivec3 f) {
  if (f == d) {
    return sh_integrate_region(sh, LPV_FAR_FACE_SOLID_ANGLE, LPV_FAR_FACE_VECTOR_D * vec3(d));
  }
  return sh_integrate_region(sh, LPV_SIDE_FACE_SOLID_ANGLE,
                             LPV_SIDE_FACE_VECTOR_F * vec3(f) + LPV_SIDE_FACE_VECTOR_D * vec3(d));
}

void main() {
  int index = int(gl_GlobalInvocationID.x) + (pc.mode == 0u ? 0 : pc.cell_begin);
  LpvOctreeCell where = lpv_octree_coords(index, int(pc.octree_levels));
  int o = where.level;
  if (o >= int(pc.octree_levels)) return;
  ivec3 c = where.c;
  int cell = index;
  int at = cell * LPV_RECORD_VEC4S;

  if (pc.mode == 0u) {
    bool counted = accumulates(o, 0u);
    for (int ch = 0; ch < 3; ++ch) {
      vec4 s = injected[at + ch];
      work[state_index(0u, cell, ch)] = s;
      accumulated[at + ch] = counted ? s : vec4(0.0);
    }
    accumulated[at + 3] = vec4(0.0, 0.0, 0.0, injected[at + 3].w);
    accumulated[at + 4] = injected[at + 4];
    return;
  }
  uint iterations = level_iterations(o);
  if (pc.step > iterations) return;

  // The flux the cell's own geometry stops of what its current state sends: light that
  // reaches the cell's surface. Negative face fluxes (SH ringing) are not counted as received
  // light.
  vec4 own_geometry = injected[at + 4];
  if (own_geometry.w > 0.0 && accumulates(o, pc.step)) {
    vec4 own[3];
    for (int ch = 0; ch < 3; ++ch) own[ch] = work[state_index(pc.src, cell, ch)];
    vec3 stopped = vec3(0.0);
    for (int a = 0; a < 6; ++a) {
      ivec3 d = AXES[a];
      float blocked = clamp(blocking(own_geometry, vec3(d)), 0.0, 1.0);
      if (blocked <= 0.0) continue;
      for (int b = 0; b < 6; ++b) {
        ivec3 f = AXES[b];
        if (f == -d) continue;
        for (int ch = 0; ch < 3; ++ch) stopped[ch] += blocked * face_flux(own[ch], d, f);
      }
    }
    accumulated[at + 3].rgb += stopped;
  }
  if (pc.step == iterations) return;

  // The neighbours are on the cell's own level.
  int level_base = lpv_level_base(o);
  int n = lpv_level_resolution(o);
  vec4 gathered[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
  for (int a = 0; a < 6; ++a) {
    ivec3 d = AXES[a];
    ivec3 source = c - d;
    if (!lpv_octree_inside(source, o)) continue;
    int source_cell = lpv_octree_cell_at(level_base, n, source, where.cascade);
    vec4 sh[3];
    for (int ch = 0; ch < 3; ++ch) sh[ch] = work[state_index(pc.src, source_cell, ch)];
    if (all(equal(sh[0], vec4(0.0))) && all(equal(sh[1], vec4(0.0))) &&
        all(equal(sh[2], vec4(0.0)))) {
      continue;
    }
    // Without a geometry volume (lpv.downsample's occlusion off) the geometry is 0: no block.
    float pass_through =
        1.0 - clamp(blocking(injected[source_cell * LPV_RECORD_VEC4S + 4], vec3(d)), 0.0, 1.0);
    for (int b = 0; b < 6; ++b) {
      ivec3 f = AXES[b];
      if (f == -d) continue;
      float omega;
      vec3 v;
      if (f == d) {
        omega = LPV_FAR_FACE_SOLID_ANGLE;
        v = LPV_FAR_FACE_VECTOR_D * vec3(d);
      } else {
        omega = LPV_SIDE_FACE_SOLID_ANGLE;
        v = LPV_SIDE_FACE_VECTOR_F * vec3(f) + LPV_SIDE_FACE_VECTOR_D * vec3(d);
      }
#if REPROJECT_DIRECTIONAL
      // The flux keeps the mean direction it crossed the face in: the projection of a delta
      // of that flux, whose integral and first moment are the flux and its direction.
      vec3 u = normalize(v);
      vec4 lobe = vec4(SH_Y0, SH_Y1 * u.y, SH_Y1 * u.z, SH_Y1 * u.x) * pass_through;
#else
      vec4 lobe = sh_clamped_cosine(vec3(f)) * (pass_through / SH_PI);
#endif
      for (int ch = 0; ch < 3; ++ch) gathered[ch] += sh_integrate_region(sh[ch], omega, v) * lobe;
    }
  }
  uint dst = 1u - pc.src;
  bool counted = accumulates(o, pc.step + 1u);
  bool lit = false;
  for (int ch = 0; ch < 3; ++ch) {
    vec4 s = gathered[ch] * pc.factor;
    // A factor above 1 grows without bound over many iterations: keep values finite.
    s = clamp(s, vec4(-3.0e37), vec4(3.0e37));
    lit = lit || any(notEqual(s, vec4(0.0)));
    work[state_index(dst, cell, ch)] = s;
    if (counted) accumulated[at + ch] = clamp(accumulated[at + ch] + s, vec4(-3.0e37), vec4(3.0e37));
  }
  // The index volume (seed 002 sec. 4.2): light landed in this cell of level o.
  if (lit && accumulated[at + 3].w < 0.0) accumulated[at + 3].w = float(o);
}
