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
