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
//   faces     rgba32ui (optional): the voxel's writers in six groups by the signed axis their
//             normal leans furthest along (0..5 = +X, -X, +Y, -Y, +Z, -Z). Per group 16 bits
//             (words 0-2, group g in the low (even g) or high half of word g / 2): the
//             direction of its mean normal as the point where it crosses the group's cube face
//             (the two other components over the axis one, 6 bits each, 62 steps over [-1, 1]:
//             bits 0-5 and 6-11) and its surface plane offset (bits 12-15, 14 steps over
//             [-1, 1] voxels, rounded up): the signed distance from the voxel centre, along the
//             group's normal, to the frontmost of its writers' planes. Word 3: per group its
//             share of the surfaces' area in the voxel (5 bits, 0..31 / 31, at least 1 for a
//             group that has any: bits 5g..5g+4). A voxel that holds a floor and a wall, or
//             the sides of a column, is lit as the surfaces it holds rather than as one plane
//             with their mean normal, each from just in front of its own surfaces
//             (docs/voxelization.md). All zero for an empty voxel.
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

// The share of a voxel's footprint seen from direction v (unit, towards the viewer) that its
// front faces cover, from the mean normal m (the normal texel's xyz, any length up to 1) as
// above: the projected front area F = mean max(n.v, 0) and back area B = mean max(-n.v, 0).
// Where both are there, each front face hides as much back area as its own (the two faces of
// a thin wall, the near and far side of a column), so the footprint is max(F, B) and the
// fronts cover F / max(F, B) of it: 1 or 0 for one plane in front or behind, 1 where the
// writers cancel (a closed surface: what shows is its front, whose light
// contracts/voxel_volumes.glsl's light shares tell), less than 1 where a surface's back hides
// part of another's front (a corner seen from behind one of its walls).
float voxel_front_share(vec3 mean_normal, vec3 v) {
  float len = length(mean_normal);
  if (!(len >= 1e-6) || isinf(len)) return 1.0;
  float c = dot(mean_normal / len, v);
  len = min(len, 1.0);
  float front = voxel_mean_clamped_cosine(len, c);
  float back = voxel_mean_clamped_cosine(len, -c);
  float footprint = max(front, back);
  return footprint > 1e-6 ? front / footprint : 1.0;
}

const int VOXEL_FACE_GROUPS = 6;
const float VOXEL_FACE_SHARE_STEPS = 31.0;
const float VOXEL_FACE_DIRECTION_HALF_STEPS = 31.0;  // codes 0..62, 31 = on the axis
const float VOXEL_FACE_OFFSET_HALF_STEPS = 7.0;      // codes 0..14, 7 = through the centre

// The axis of group g, and its two other axes.
ivec3 voxel_face_axes(int g) {
  int a = g >> 1;
  return ivec3(a, (a + 1) % 3, (a + 2) % 3);
}

// Adds group g (unit mean-normal direction leaning furthest along the group's axis, area share
// in (0, 1], plane offset in voxels) to a faces texel. The offset is rounded up, so that the
// encoded plane never lies behind a writer's.
uvec4 voxel_pack_face(uvec4 faces, int g, vec3 direction, float share, float plane_offset) {
  ivec3 axes = voxel_face_axes(g);
  float major = max(abs(direction[axes.x]), 1e-6);
  vec2 face = clamp(vec2(direction[axes.y], direction[axes.z]) / major, -1.0, 1.0);
  uvec2 e = uvec2(round((face + 1.0) * VOXEL_FACE_DIRECTION_HALF_STEPS));
  float d = clamp(plane_offset, -1.0, 1.0);
  uint o = uint(clamp(ceil((d + 1.0) * VOXEL_FACE_OFFSET_HALF_STEPS - 1e-3), 0.0,
                      2.0 * VOXEL_FACE_OFFSET_HALF_STEPS));
  uint bits = e.x | (e.y << 6) | (o << 12);
  faces[g >> 1] |= bits << (16 * (g & 1));
  uint steps = uint(clamp(round(share * VOXEL_FACE_SHARE_STEPS), 1.0, VOXEL_FACE_SHARE_STEPS));
  faces.w |= steps << (5 * g);
  return faces;
}

// Area share of group g (0: none); the shares of a texel add up to about 1.
float voxel_face_share(uvec4 faces, int g) {
  return float((faces.w >> (5 * g)) & 31u) / VOXEL_FACE_SHARE_STEPS;
}
uint voxel_face_bits(uvec4 faces, int g) { return (faces[g >> 1] >> (16 * (g & 1))) & 0xFFFFu; }
vec3 voxel_face_normal(uvec4 faces, int g) {
  uint bits = voxel_face_bits(faces, g);
  ivec3 axes = voxel_face_axes(g);
  vec3 n;
  n[axes.x] = (g & 1) == 0 ? 1.0 : -1.0;
  n[axes.y] = float(bits & 63u) / VOXEL_FACE_DIRECTION_HALF_STEPS - 1.0;
  n[axes.z] = float((bits >> 6) & 63u) / VOXEL_FACE_DIRECTION_HALF_STEPS - 1.0;
  return normalize(n);
}
// Signed distance in voxels from the voxel centre to group g's frontmost plane, along its normal.
float voxel_face_offset(uvec4 faces, int g) {
  return float(voxel_face_bits(faces, g) >> 12) / VOXEL_FACE_OFFSET_HALF_STEPS - 1.0;
}

// The groups a faces texel holds, by group index g (0..5): their unit normals, their shares,
// rescaled to add up to exactly 1 (the 5-bit shares only nearly do), and their plane offsets
// (voxels); share 0 (normal and offset 0) for a group the voxel does not hold. Returns how many
// it holds (0: no faces, e.g. a voxel of average_rgba8 or an empty one).
int voxel_faces_unpack(uvec4 faces, out vec3 normals[VOXEL_FACE_GROUPS],
                       out float shares[VOXEL_FACE_GROUPS], out float offsets[VOXEL_FACE_GROUPS]) {
  int count = 0;
  float total = 0.0;
  for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
    shares[g] = voxel_face_share(faces, g);
    bool held = shares[g] > 0.0;
    normals[g] = held ? voxel_face_normal(faces, g) : vec3(0.0);
    offsets[g] = held ? voxel_face_offset(faces, g) : 0.0;
    total += shares[g];
    count += held ? 1 : 0;
  }
  if (count > 0) {
    for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) shares[g] /= total;
  }
  return count;
}
int voxel_faces_unpack(uvec4 faces, out vec3 normals[VOXEL_FACE_GROUPS],
                       out float shares[VOXEL_FACE_GROUPS]) {
  float offsets[VOXEL_FACE_GROUPS];
  return voxel_faces_unpack(faces, normals, shares, offsets);
}

// Light shares (r32ui, optional, written by an injection beside its radiance clipmap): per
// face group g (the groups of the faces texel), the share of the voxel's outgoing light
// (luminance times area) that the group's surfaces send, 5 bits at bit 5g (0..31 / 31). A voxel
// whose groups are lit alike holds their area shares; a thin wall lit on one face holds all of
// its light in that face's group, so that vct.filter sends it only that way. 0: no light, or
// no faces (the voxel's light is then spread as its area is).
const float VOXEL_LIGHT_SHARE_STEPS = 31.0;
float voxel_luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }
uint voxel_pack_light_share(uint shares, int g, float share) {
  return shares | (uint(round(clamp(share, 0.0, 1.0) * VOXEL_LIGHT_SHARE_STEPS)) << (5 * g));
}
float voxel_light_share(uint shares, int g) {
  return float((shares >> (5 * g)) & 31u) / VOXEL_LIGHT_SHARE_STEPS;
}
// The light shares of a voxel whose groups send `group_light` (luminance x area share, 0 for
// a group it does not hold): 0 where it sends none.
uint voxel_pack_light_shares(float group_light[VOXEL_FACE_GROUPS]) {
  float light = 0.0;
  for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) light += group_light[g];
  uint shares = 0u;
  if (!(light > 0.0) || isinf(light)) return shares;
  for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
    shares = voxel_pack_light_share(shares, g, group_light[g] / light);
  }
  return shares;
}
// The light shares of a texel, by group index, rescaled to add up to exactly 1; false (all 0)
// where it holds none.
bool voxel_light_shares_unpack(uint bits, out float shares[VOXEL_FACE_GROUPS]) {
  float total = 0.0;
  for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
    shares[g] = voxel_light_share(bits, g);
    total += shares[g];
  }
  if (!(total > 0.0)) return false;
  for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) shares[g] /= total;
  return true;
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
