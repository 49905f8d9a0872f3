#version 460
// Voxelization: for the pixel column of this fragment, finds the voxels of the box that the
// triangle really overlaps (at most three along the projection axis; an exact separating-axis
// test, see voxel_triangle.glsl), evaluates the material at each voxel's centre (projected
// on the triangle) and adds it into the scratch record of that voxel. With
// VOXEL_CONSERVATIVE == 0 the classic non-conservative rule applies instead: the one voxel at
// the pixel centre's depth.

#define SCENE_TEXTURE_EXPLICIT_LOD
#include "lib/common.glsl"
#include "lib/scene.glsl"
#include "common/voxel_draw.glsl"
#include "common/voxel_accumulate.glsl"

#define VOXEL_TRIANGLE_QUALIFIER in
#include "common/voxel_triangle.glsl"

#ifndef VOXEL_CONSERVATIVE
#define VOXEL_CONSERVATIVE 1
#endif
// 0: every fragment accumulates; 1: the draw that records the front surfaces; 2: the draw that
// accumulates what they leave visible.
#ifndef VOXEL_FRONT
#define VOXEL_FRONT 0
#endif

bool overlaps(ivec3 voxel) {
  vec3 p = vec3(voxel);
  // Bounding boxes.
  if (any(greaterThan(p, tri_aabb_max + VOXEL_OVERLAP_EPSILON)) ||
      any(lessThan(p + 1.0, tri_aabb_min - VOXEL_OVERLAP_EPSILON))) {
    return false;
  }
  vec3 q = p - tri_v0;
  // Plane: the box's lowest and highest corners along the normal straddle it. A plane lying on
  // a face between two voxels belongs to the one in front of it (on its normal's side), as a
  // plane just in front of the face would: the box whose highest corner only touches the plane
  // lies behind the surface. (Both, as any touch counts elsewhere, made walls on voxel faces two
  // voxels thick, with the receiver's own surface half a voxel above it.)
  float s = dot(tri_plane.xyz, q);
  if (s + tri_plane_d.x > VOXEL_OVERLAP_EPSILON || s + tri_plane_d.y <= VOXEL_OVERLAP_EPSILON) {
    return false;
  }
  // Edges in the three projections (xy, yz, zx).
  vec2 projected[3] = vec2[3](q.xy, q.yz, q.zx);
  for (int i = 0; i < 9; ++i) {
    vec3 e = tri_edges[i];
    if (dot(e.xy, projected[i / 3]) + e.z < -VOXEL_OVERLAP_EPSILON) return false;
  }
  return true;
}

// Sutherland-Hodgman step: the part of the convex polygon on the side of the line where
// dot(line.xy, p) + line.z >= 0. A triangle clipped by four lines has at most 7 vertices.
void clip_polygon(inout vec2 poly[8], inout int count, vec3 line) {
  vec2 result[8];
  int kept = 0;
  for (int i = 0; i < count; ++i) {
    vec2 a = poly[i], b = poly[(i + 1) % count];
    float da = dot(line.xy, a) + line.z, db = dot(line.xy, b) + line.z;
    if (da >= 0.0 && kept < 8) result[kept++] = a;
    if ((da >= 0.0) != (db >= 0.0) && kept < 8) result[kept++] = mix(a, b, da / (da - db));
  }
  poly = result;
  count = kept;
}

// The fraction of the voxel's cross-section along `axis` (its face, the unit square at the
// anchored corner) that the triangle covers, seen along that axis, the dominant axis of its
// normal. A column through the inside of a surface is covered whole, whatever the surface's
// slope; one at its edge in part. The voxel's emission weighs each surface by it
// (voxel_accumulate.glsl). In anchored coordinates, so that a scrolled window gives the same.
float column_coverage(int axis, vec3 corner) {
  int u = axis == 2 ? 0 : (axis == 0 ? 1 : 2);
  int v = axis == 2 ? 1 : (axis == 0 ? 2 : 0);
  vec2 poly[8];
  for (int i = 0; i < 3; ++i) poly[i] = vec2(tri_anchored[i][u] - corner[u], tri_anchored[i][v] - corner[v]);
  int count = 3;
  clip_polygon(poly, count, vec3(1.0, 0.0, 0.0));
  clip_polygon(poly, count, vec3(-1.0, 0.0, 1.0));
  clip_polygon(poly, count, vec3(0.0, 1.0, 0.0));
  clip_polygon(poly, count, vec3(0.0, -1.0, 1.0));
  float twice_area = 0.0;
  for (int i = 0; i < count; ++i) {
    vec2 a = poly[i], b = poly[(i + 1) % count];
    twice_area += a.x * b.y - a.y * b.x;
  }
  return clamp(0.5 * abs(twice_area), 0.0, 1.0);
}

// column_share: 1 / the number of voxels of its column this fragment writes (the part of the
// triangle's area in the column each of them gets, for the faces' area weights).
void store(ivec3 voxel, float column_share) {
  // Material at the voxel centre projected on the triangle, barycentrics clamped inside it.
  vec3 q = vec3(voxel) + 0.5 - tri_v0;
  q -= tri_plane.xyz * dot(tri_plane.xyz, q);
  float b1 = dot(q, tri_bary1), b2 = dot(q, tri_bary2);
  vec3 bary = max(vec3(1.0 - b1 - b2, b1, b2), vec3(0.0));
  float sum = bary.x + bary.y + bary.z;
  bary = sum > 1e-6 ? bary / sum : vec3(1.0 / 3.0);
  SurfaceAttributes attributes;
  attributes.uv0 = tri_uv01.xy * bary.x + tri_uv01.zw * bary.y + tri_uv2.xy * bary.z;
  attributes.uv1 = tri_uv1_01.xy * bary.x + tri_uv1_01.zw * bary.y + tri_uv2.zw * bary.z;
  vec4 c0 = vec4(unpackHalf2x16(tri_colors01.x), unpackHalf2x16(tri_colors01.y));
  vec4 c1 = vec4(unpackHalf2x16(tri_colors01.z), unpackHalf2x16(tri_colors01.w));
  vec4 c2 = vec4(unpackHalf2x16(tri_color2.x), unpackHalf2x16(tri_color2.y));
  attributes.color = c0 * bary.x + c1 * bary.y + c2 * bary.z;
  vec3 interpolated =
      tri_normals[0] * bary.x + tri_normals[1] * bary.y + tri_normals[2] * bary.z;
  // Zero or cancelling vertex normals fall back to the face normal (window axes are world axes).
  vec3 normal = safe_normalize(interpolated, tri_plane.xyz);

  uint instance = tri_instance_axis.x;
  scene_texture_lod = tri_plane.w;
  MaterialSample m = sample_material(scene_instances[instance].material, attributes, normal, vec4(0.0));
  if (m.alpha_mask && m.base_color.a < m.alpha_cutoff) return;
  ivec3 local = voxel - voxel_draw.box_min.xyz;
  ivec3 extent = voxel_draw.box_max.xyz - voxel_draw.box_min.xyz;
  uint index = uint((local.z * extent.y + local.y) * extent.x + local.x);
  uint stride = uint(voxel_draw.box_max.w);
  uint base = index * stride;
  // The face normal and the voxel's corner in anchored coordinates (see column_coverage).
  vec3 face = tri_anchored_normal;
  vec3 corner = vec3(voxel + voxel_draw.origin.xyz);
#if VOXEL_FRONT != 0
  // Stacked surfaces (voxel_accumulate.glsl): the first draw finds the frontmost opaque surface
  // per facing, the second keeps only what that surface leaves visible.
  float depth = dot(face, tri_anchored[0] - (corner + 0.5));
  uint key = voxel_front_key(depth, instance);
  uint front_word = base + stride - VOXEL_FRONT_WORDS + voxel_front_axis(face);
#if VOXEL_FRONT == 1
  if (!m.alpha_blend || m.base_color.a >= 1.0) atomicMax(voxel_scratch[front_word], key);
  return;
#else
  if (!voxel_front_visible(key, voxel_scratch[front_word])) return;
#endif
#endif
  vec3 albedo = m.base_color.rgb * (1.0 - m.metallic);  // the glTF BRDF's diffuse albedo
  vec3 emission = sanitize_radiance(m.emissive);
  vec3 n = safe_normalize(m.normal, tri_plane.xyz);
#ifdef VOXEL_STRATEGY_RGBA8
  voxel_average_rgba8(base, albedo);
  voxel_average_rgba8(base + 1u, n * 0.5 + 0.5);
#ifdef VOXEL_HAS_EMISSION
  voxel_average_rgba8(base + 2u, emission);
#endif
#else
  // The triangle's plane relative to this voxel's centre, along the shading normal (voxels).
  float plane_offset = -dot(tri_plane.xyz, vec3(voxel) + 0.5 - tri_v0) * dot(n, tri_plane.xyz);
#if defined(VOXEL_HAS_EMISSION) || defined(VOXEL_FACES)
  vec3 a = abs(face);
  int coverage_axis = (a.z >= a.x && a.z >= a.y) ? 2 : (a.x >= a.y ? 0 : 1);
  float coverage = column_coverage(coverage_axis, corner);
#else
  float coverage = 1.0;  // weighs the emission only
#endif
  voxel_accumulate_hdr(base, coverage, albedo, m.base_color.a, n, plane_offset, emission);
#ifdef VOXEL_FACES
  // The triangle's area in this voxel (voxel faces): its area in the column, the covered part
  // of the column's cross-section over the cosine to the column's axis, shared out among the
  // voxels of the column it writes.
  float area = coverage / max(a[coverage_axis], 1e-3) * column_share;
#ifdef VOXEL_HAS_EMISSION
  voxel_accumulate_face(base + VOXEL_HDR_WORDS_WITH_EMISSION, n, area, plane_offset);
#else
  voxel_accumulate_face(base + VOXEL_HDR_WORDS, n, area, plane_offset);
#endif
#endif
#endif
}

void main() {
  int axis = int(tri_instance_axis.y);
  int u = axis == 2 ? 0 : (axis == 0 ? 1 : 2);
  int v = axis == 2 ? 1 : (axis == 0 ? 2 : 0);
  ivec3 box_min = voxel_draw.box_min.xyz, box_max = voxel_draw.box_max.xyz;
  ivec3 voxel = ivec3(0);
  voxel[u] = int(gl_FragCoord.x) + box_min[u];
  voxel[v] = int(gl_FragCoord.y) + box_min[v];
  if (voxel[u] >= box_max[u] || voxel[v] >= box_max[v]) return;

  // Depth of the triangle's plane along the projection axis over this pixel column.
  vec3 n = tri_plane.xyz;
  float cu = float(voxel[u]) + 0.5 - tri_v0[u], cv = float(voxel[v]) + 0.5 - tri_v0[v];
  float center = tri_v0[axis] - (n[u] * cu + n[v] * cv) / n[axis];
#if VOXEL_CONSERVATIVE == 0
  voxel[axis] = int(floor(center));
  if (voxel[axis] >= box_min[axis] && voxel[axis] < box_max[axis]) store(voxel, 1.0);
#else
  float half_range = 0.5 * (abs(n[u]) + abs(n[v])) / abs(n[axis]);
  float lo = max(center - half_range, tri_aabb_min[axis]) - VOXEL_OVERLAP_EPSILON;
  float hi = min(center + half_range, tri_aabb_max[axis]) + VOXEL_OVERLAP_EPSILON;
  int first = max(int(floor(lo)), box_min[axis]);
  int last = min(min(int(floor(hi)), box_max[axis] - 1), first + 3);
  // The voxels (at most four) the triangle overlaps, found once: the faces' area weights need
  // their count before any of them is stored.
  uint overlapped = 0u;
  int written = 0;
  for (int k = first; k <= last; ++k) {
    voxel[axis] = k;
    if (overlaps(voxel)) {
      overlapped |= 1u << uint(k - first);
      ++written;
    }
  }
  for (int k = first; k <= last; ++k) {
    voxel[axis] = k;
    if ((overlapped & (1u << uint(k - first))) != 0u) store(voxel, 1.0 / float(written));
  }
#endif
}
