#version 460
#extension GL_GOOGLE_include_directive : require
// lpv.propagate: the injected intensities spread cell to cell (seed 002 sec. 3.2.3; docs/lpv.md).
//
// MODE 0: decodes the fixed-point injection into state 0 and the accumulation (S_0), and
//         builds the geometry volume (blocking potential as SH) from the voxels.
// MODE 1: one iteration from state `src` into state `1 - src`: a cell B gathers from each
//         axial neighbour A the flux A's intensity sends through each of B's five faces that do
//         not face A, the exact integral of A's SH over the face as seen from A's centre
//         (lpv/sh.glsl), and re-emits it from its centre as a Lambertian lobe along the face's
//         normal: flux / pi x max(0, f.w). The 6 x 5 faces partition the sphere, so at factor 1
//         the total flux is carried, not created. Light crossing into B is multiplied by
//         1 - B's blocking towards the direction of travel (with occlusion on); light that
//         leaves the window is lost. The accumulation adds each iteration: S = sum S_i.
#include "lib/common.glsl"
#include "lpv/sh.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#include "contracts/voxel_volumes.glsl"
#include "lpv/cells.glsl"

#ifndef REPROJECT_DIRECTIONAL
#define REPROJECT_DIRECTIONAL 0
#endif
#ifndef HAS_OCCLUSION
#define HAS_OCCLUSION 0
#endif

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(set = 0, binding = 1, std430) readonly buffer Injected {
  uint max_magnitude_bits;
  uint contributions;
  uint pad0;
  uint pad1;
  int coefficients[];
} injected;
// States 0 and 1 (cells x 3 vec4 each), then the geometry volume (cells vec4).
layout(set = 0, binding = 2, std430) buffer Work { vec4 work[]; };
// Per cell (lpv/cells.glsl, LPV_RADIANCE_VEC4S): the accumulated SH intensity per channel, the
// flux its geometry stopped (rgb), and its geometry (normal, opacity).
layout(set = 0, binding = 3, std430) buffer Accumulated { vec4 accumulated[]; };
#if HAS_OCCLUSION
layout(set = 0, binding = 4) uniform sampler3D voxel_albedo;
layout(set = 0, binding = 5) uniform sampler3D voxel_normal;
#endif

layout(push_constant) uniform Push {
  uint mode;
  uint src;      // state read by MODE 1
  float factor;  // propagation factor (1: physical)
  uint pad;
} pc;

int state_index(uint state, int cell, int ch) { return (int(state) * lpv_cell_total() + cell) * 3 + ch; }
int geometry_index(int cell) { return 2 * 3 * lpv_cell_total() + cell; }

#if HAS_OCCLUSION
// The geometry of a voxel: its mean normal m (|m| <= 1; ~0 where opposite faces share the
// voxel) and its opacity.
vec4 voxel_geometry(ivec3 c, int level) {
  if (!voxel_level_valid(level)) return vec4(0.0);
  ivec3 t = voxel_texel(c, level);
  vec4 n = texelFetch(voxel_normal, t, 0);
  float opacity = clamp(texelFetch(voxel_albedo, t, 0).a, 0.0, 1.0);
  if (!voxel_normal_occupied(n) || !(opacity > 0.0)) return vec4(0.0);
  vec3 m = n.xyz;
  float len = length(m);
  if (!(len <= 1.0)) m = len > 1.0 ? m / len : vec3(0.0);
  return vec4(m, opacity);
}
#endif

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
  ivec3 id = ivec3(gl_GlobalInvocationID);
  int r = voxel_resolution();
  int level = id.z / r;
  ivec3 c = ivec3(id.xy, id.z % r);
  if (level >= voxel_level_count() || any(greaterThanEqual(id.xy, ivec2(r)))) return;
  int cell = lpv_cell(c, level);

  if (pc.mode == 0u) {
    float scale = lpv_fixed_point_scale(injected.max_magnitude_bits, injected.contributions);
    for (int ch = 0; ch < 3; ++ch) {
      vec4 s = vec4(0.0);
      if (scale > 0.0) {
        int base = cell * 12 + ch * 4;
        s = vec4(injected.coefficients[base], injected.coefficients[base + 1],
                 injected.coefficients[base + 2], injected.coefficients[base + 3]) / scale;
      }
      work[state_index(0u, cell, ch)] = s;
      accumulated[cell * LPV_RADIANCE_VEC4S + ch] = s;
    }
    accumulated[cell * LPV_RADIANCE_VEC4S + 3] = vec4(0.0);
    vec4 gv = vec4(0.0);
#if HAS_OCCLUSION
    gv = voxel_geometry(c, level);
#endif
    work[geometry_index(cell)] = gv;
    accumulated[cell * LPV_RADIANCE_VEC4S + 4] = gv;
    return;
  }

  // The flux the cell's own geometry stops of what its current state sends (MODE 1 and the
  // final MODE 2): light that reaches the cell's surface. Negative face fluxes (SH ringing)
  // are not counted as received light.
  vec4 own_geometry = work[geometry_index(cell)];
  if (own_geometry.w > 0.0) {
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
    accumulated[cell * LPV_RADIANCE_VEC4S + 3].rgb += stopped;
  }
  if (pc.mode == 2u) return;

  vec4 gathered[3] = vec4[3](vec4(0.0), vec4(0.0), vec4(0.0));
  for (int a = 0; a < 6; ++a) {
    ivec3 d = AXES[a];
    ivec3 source = c - d;
    if (!lpv_inside(source)) continue;
    int source_cell = lpv_cell(source, level);
    vec4 sh[3];
    for (int ch = 0; ch < 3; ++ch) sh[ch] = work[state_index(pc.src, source_cell, ch)];
    if (all(equal(sh[0], vec4(0.0))) && all(equal(sh[1], vec4(0.0))) &&
        all(equal(sh[2], vec4(0.0)))) {
      continue;
    }
    float pass_through = 1.0;
#if HAS_OCCLUSION
    pass_through = 1.0 - clamp(blocking(work[geometry_index(source_cell)], vec3(d)), 0.0, 1.0);
#endif
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
  for (int ch = 0; ch < 3; ++ch) {
    vec4 s = gathered[ch] * pc.factor;
    // A factor above 1 grows without bound over many iterations: keep values finite.
    s = clamp(s, vec4(-3.0e37), vec4(3.0e37));
    work[state_index(dst, cell, ch)] = s;
    int at = cell * LPV_RADIANCE_VEC4S + ch;
    accumulated[at] = clamp(accumulated[at] + s, vec4(-3.0e37), vec4(3.0e37));
  }
}
