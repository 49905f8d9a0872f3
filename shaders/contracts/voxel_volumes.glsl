#ifndef VOXGI_VOXEL_VOLUMES_GLSL
#define VOXGI_VOXEL_VOLUMES_GLSL
// Contract: the voxel volumes common.voxelize writes and every voxel family reads (clipmaps
// addressed as contracts/voxel_clipmap.glsl describes). C++ twin:
// passes/contracts/voxel_volumes.hpp (the formats). No bindings.
//
//   albedo    rgba8 unorm: rgb linear diffuse albedo, a opacity (0 = empty voxel)
//   normal    rgba16f: xyz the average of the writers' unit normals (length <= 1, ~0 where
//             opposite faces share a voxel); w = 1 + d / 4 for an occupied voxel (0 for an
//             empty one), d the signed distance in voxels from the voxel centre to the
//             average surface plane along that normal, |d| <= 1
//   emission  rgba16f (optional): rgb emitted radiance, finite and below the half maximum
//
// Lighting is evaluated on the surface (centre + d * n), not at the centre: near a light the
// centre can be half a voxel closer to it than any surface in the voxel, and 1/r^2 makes that
// a large error.
const float VOXEL_PLANE_OFFSET_SCALE = 0.25;
// An averaged normal shorter than this comes from writers whose faces cancelled (both faces of
// a thin wall, a crease): such a voxel has no facing.
const float VOXEL_NORMAL_MIN_LENGTH = 0.25;
bool voxel_normal_occupied(vec4 normal_texel) { return normal_texel.w > 0.5; }
// The mean over a voxel's writers of their clamped cosine max(n_i . v, 0) towards a unit
// direction v, from their mean normal m = mean(n_i) alone: `len` = |m| (0..1) and c = the
// cosine between m and v. The writers' normals are taken to be the least-structured spread
// with that mean: a fraction 2|m| - 1 along m and the rest spread evenly over the hemisphere
// around m (whose mean is m/2) where |m| >= 1/2; below that, a hemisphere and a uniform sphere
// (mean 0). An even hemisphere's mean clamped cosine is (1 + cos theta) / 4 and a sphere's
// 1/4. Exact for one plane (|m| = 1), a right-angled corner seen along its bisector, a half
// cylinder seen head-on and a sphere.
float voxel_mean_clamped_cosine(float len, float c) {
  if (len <= 0.5) return 0.25 + 0.5 * len * c;
  return (2.0 * len - 1.0) * max(c, 0.0) + (1.0 - len) * 0.5 * (1.0 + c);
}

// The share of a voxel's surface seen from direction v (unit, towards the viewer) that faces
// the viewer: projected front area over all projected area, mean max(n.v, 0) over
// mean |n.v|, from the mean normal m (the normal texel's xyz, any length up to 1) as above. 1 or 0 for one plane in front or behind, 1/2
// where the writers cancel (a thin wall's two faces).
float voxel_front_share(vec3 mean_normal, vec3 v) {
  float len = length(mean_normal);
  if (!(len >= 1e-6) || isinf(len)) return 0.5;
  float c = dot(mean_normal / len, v);
  len = min(len, 1.0);
  float front = voxel_mean_clamped_cosine(len, c);
  float back = voxel_mean_clamped_cosine(len, -c);
  return front + back > 1e-6 ? front / (front + back) : 0.5;
}

float voxel_encode_plane_offset(float d) {
  return 1.0 + VOXEL_PLANE_OFFSET_SCALE * clamp(d, -1.0, 1.0);
}
// d in voxels (0 for an empty voxel or a non-finite value).
float voxel_plane_offset(vec4 normal_texel) {
  float w = normal_texel.w;
  if (!(w > 0.5) || isinf(w)) return 0.0;
  return clamp((w - 1.0) / VOXEL_PLANE_OFFSET_SCALE, -1.0, 1.0);
}

#endif
