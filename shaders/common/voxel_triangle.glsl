#ifndef VOXGI_VOXEL_TRIANGLE_GLSL
#define VOXGI_VOXEL_TRIANGLE_GLSL
// The per-triangle data the voxelization geometry shader hands to the fragment shader (flat),
// so that the fragment shader can run an exact triangle/voxel overlap test (the separating
// axis test in the form of Schwarz and Seidel 2010: the triangle's plane, the triangle's
// bounding box and three edge tests in each of the three axis-aligned projections) and
// evaluate attributes at voxel centres. Everything is relative to the triangle's first
// vertex v0, in window voxel units, so that magnitudes stay small.
//
// VOXEL_TRIANGLE_QUALIFIER is `out` in the geometry shader and `in` in the fragment shader.

layout(location = 0) flat VOXEL_TRIANGLE_QUALIFIER vec4 tri_plane;    // xyz unit normal; w: texture lod
layout(location = 1) flat VOXEL_TRIANGLE_QUALIFIER vec2 tri_plane_d;  // box-min-corner offsets (below)
layout(location = 2) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_aabb_min;  // window coordinates
layout(location = 3) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_aabb_max;
layout(location = 4) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_edges[9];  // (normal.xy, offset) xy, yz, zx
layout(location = 13) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_v0;       // window coordinates
layout(location = 14) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_bary1;    // barycentric b1 = dot(q - v0, bary1)
layout(location = 15) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_bary2;
layout(location = 16) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_normals[3];  // world vertex normals
layout(location = 19) flat VOXEL_TRIANGLE_QUALIFIER vec4 tri_uv01;
layout(location = 20) flat VOXEL_TRIANGLE_QUALIFIER vec4 tri_uv2;  // xy: TEXCOORD_0 of v2, zw: TEXCOORD_1
layout(location = 21) flat VOXEL_TRIANGLE_QUALIFIER uvec2 tri_instance_axis;  // instance, dominant axis
// The vertices in anchored coordinates (voxel_draw.glsl), for coverage and front-surface keys.
layout(location = 22) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_anchored[3];
layout(location = 25) flat VOXEL_TRIANGLE_QUALIFIER vec3 tri_anchored_normal;  // unit face normal
layout(location = 26) flat VOXEL_TRIANGLE_QUALIFIER vec4 tri_uv1_01;  // TEXCOORD_1 of v0 and v1
// COLOR_0 of the vertices as half floats (packHalf2x16 of rg, ba): v0, v1 in the first, v2 in
// the second; the voxels keep the base colour far coarser than half precision anyway.
layout(location = 27) flat VOXEL_TRIANGLE_QUALIFIER uvec4 tri_colors01;
layout(location = 28) flat VOXEL_TRIANGLE_QUALIFIER uvec2 tri_color2;

// Tolerance of the overlap test in voxels: covers float rounding of window coordinates up to a
// few hundred voxels; it adds voxels that touch the triangle within this distance.
const float VOXEL_OVERLAP_EPSILON = 2e-4;

#endif
