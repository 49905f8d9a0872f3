#version 460
// Voxelization: projects each triangle on the axis its normal is most aligned with (so its
// projection has the largest area) and makes the rasterizer produce a fragment for every
// pixel column the triangle touches. VOXEL_CONSERVATIVE: 0 = plain rasterization (pixel
// centres), 1 = enlarge the triangle here (every edge pushed out by half a pixel diagonal;
// slivers whose enlarged corners would fly far out get their bounding square instead),
// 2 = the rasterizer is conservative (VK_EXT_conservative_rasterization). The fragment shader
// then keeps exactly the voxels the triangle overlaps.

#include "lib/scene.glsl"
#include "common/voxel_draw.glsl"

#define VOXEL_TRIANGLE_QUALIFIER out
#include "common/voxel_triangle.glsl"

#ifndef VOXEL_CONSERVATIVE
#define VOXEL_CONSERVATIVE 1
#endif

layout(triangles) in;
layout(triangle_strip, max_vertices = 4) out;

layout(location = 0) in vec3 in_window[];
layout(location = 1) in vec3 in_normal[];
layout(location = 2) in vec2 in_uv[];
layout(location = 3) flat in uint in_instance[];
layout(location = 4) in vec3 in_anchored[];
layout(location = 5) in vec2 in_uv1[];
layout(location = 6) in vec4 in_color[];

vec3 g_edges[9];

// The three edge tests of one axis-aligned projection. (a, b) are the projection's axes and
// k the remaining one; orientation makes the edge normals point inwards.
void write_edges(int first, vec3 p[3], int a, int b, float orientation) {
  for (int i = 0; i < 3; ++i) {
    vec3 e = p[(i + 1) % 3] - p[i];
    vec2 n = vec2(-e[b], e[a]) * orientation;
    float len2 = dot(n, n);
    if (len2 > 1e-24) {
      n *= inversesqrt(len2);
      float d = -(n.x * p[i][a] + n.y * p[i][b]) + max(0.0, n.x) + max(0.0, n.y);
      g_edges[first + i] = vec3(n, d);
    } else {
      g_edges[first + i] = vec3(0.0);  // a point in this projection: no constraint
    }
  }
}

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

vec2 project(vec3 window, int axis) {
  vec3 local = window - vec3(voxel_draw.box_min.xyz);
  if (axis == 2) return local.xy;
  if (axis == 0) return local.yz;
  return local.zx;
}

// Outputs are undefined after EmitVertex(), so every vertex writes the flat data again.
vec4 g_plane;
vec2 g_plane_d;
vec3 g_aabb_min, g_aabb_max, g_v0, g_bary1, g_bary2, g_anchored_normal;
uvec2 g_instance_axis;

void emit_at(vec2 pixel) {
  tri_plane = g_plane;
  tri_plane_d = g_plane_d;
  tri_aabb_min = g_aabb_min;
  tri_aabb_max = g_aabb_max;
  for (int i = 0; i < 9; ++i) tri_edges[i] = g_edges[i];
  tri_v0 = g_v0;
  tri_anchored[0] = in_anchored[0];
  tri_anchored[1] = in_anchored[1];
  tri_anchored[2] = in_anchored[2];
  tri_anchored_normal = g_anchored_normal;
  tri_bary1 = g_bary1;
  tri_bary2 = g_bary2;
  tri_normals[0] = in_normal[0];
  tri_normals[1] = in_normal[1];
  tri_normals[2] = in_normal[2];
  tri_uv01 = vec4(in_uv[0], in_uv[1]);
  tri_uv2 = vec4(in_uv[2], in_uv1[2]);
  tri_uv1_01 = vec4(in_uv1[0], in_uv1[1]);
  tri_colors01 = uvec4(packHalf2x16(in_color[0].rg), packHalf2x16(in_color[0].ba),
                       packHalf2x16(in_color[1].rg), packHalf2x16(in_color[1].ba));
  tri_color2 = uvec2(packHalf2x16(in_color[2].rg), packHalf2x16(in_color[2].ba));
  tri_instance_axis = g_instance_axis;
  float size = float(voxel_draw.box_min.w);
  gl_Position = vec4(pixel / size * 2.0 - 1.0, 0.5, 1.0);
  EmitVertex();
}

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

void main() {
  vec3 w0 = in_window[0], w1 = in_window[1], w2 = in_window[2];
  if (!finite3(w0) || !finite3(w1) || !finite3(w2)) return;
  vec3 e1 = w1 - w0, e2 = w2 - w0;
  vec3 n = cross(e1, e2);
  float n_len2 = dot(n, n);
  float scale2 = max(dot(e1, e1), dot(e2, e2));
  // Zero-area triangles (repeated or collinear vertices) cover no surface: nothing to store,
  // and every normal or barycentric below would divide by zero.
  if (!(n_len2 > 1e-12 * scale2 * scale2) || isinf(n_len2)) return;
  vec3 unit = n * inversesqrt(n_len2);

  vec3 a = abs(n);
  int axis = (a.z >= a.x && a.z >= a.y) ? 2 : (a.x >= a.y ? 0 : 1);

  // Flat data for the overlap test, relative to v0.
  vec3 rel[3] = vec3[3](vec3(0.0), e1, e2);
  float lod = 0.0;
  {
    // The base colour's footprint: its texture coordinates at the three vertices.
    SceneMaterial m = scene_materials[scene_instances[in_instance[0]].material];
    vec2 t[3];
    for (int i = 0; i < 3; ++i) {
      t[i] = scene_texture_coords(m, 0u, SurfaceAttributes(in_uv[i], in_uv1[i], vec4(1.0)));
    }
    vec2 tex = vec2(textureSize(scene_textures_srgb, 0).xy);
    vec2 duv1 = (t[1] - t[0]) * tex, duv2 = (t[2] - t[0]) * tex;
    float texel_area = abs(cross2(duv1, duv2));
    float ratio = texel_area / sqrt(n_len2);  // texels per voxel face (both areas doubled)
    lod = ratio > 1.0 ? clamp(0.5 * log2(ratio), 0.0, 16.0) : 0.0;
  }
  g_plane = vec4(unit, lod);
  g_plane_d = vec2(dot(min(unit, vec3(0.0)), vec3(1.0)), dot(max(unit, vec3(0.0)), vec3(1.0)));
  g_aabb_min = min(w0, min(w1, w2));
  g_aabb_max = max(w0, max(w1, w2));
  write_edges(0, rel, 0, 1, unit.z < 0.0 ? -1.0 : 1.0);
  write_edges(3, rel, 1, 2, unit.x < 0.0 ? -1.0 : 1.0);
  write_edges(6, rel, 2, 0, unit.y < 0.0 ? -1.0 : 1.0);
  g_v0 = w0;
  g_anchored_normal =
      normalize(cross(in_anchored[1] - in_anchored[0], in_anchored[2] - in_anchored[0]));
  // Barycentrics of a point q on the plane: b1 = dot(q - v0, bary1), b2 = dot(q - v0, bary2).
  float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
  g_bary1 = (d11 * e1 - d01 * e2) / n_len2;
  g_bary2 = (d00 * e2 - d01 * e1) / n_len2;
  g_instance_axis = uvec2(in_instance[0], uint(axis));

  vec2 p[3] = vec2[3](project(w0, axis), project(w1, axis), project(w2, axis));
#if VOXEL_CONSERVATIVE == 1
  if (cross2(p[1] - p[0], p[2] - p[0]) < 0.0) {
    vec2 t = p[1];
    p[1] = p[2];
    p[2] = t;
  }
  // Outward edge lines pushed out by half the pixel diagonal along their normal (plus a
  // margin for the rasterizer's subpixel snapping); corners where adjacent lines meet.
  vec2 m[3];
  float c[3];
  for (int i = 0; i < 3; ++i) {
    vec2 e = p[(i + 1) % 3] - p[i];
    m[i] = vec2(e.y, -e.x);
    c[i] = dot(m[i], p[i]) + (0.5 + 1.0 / 64.0) * (abs(m[i].x) + abs(m[i].y));
  }
  vec2 corner[3];
  bool sliver = false;
  for (int i = 0; i < 3; ++i) {
    int j = (i + 2) % 3;  // the edge ending at vertex i
    float det = cross2(m[j], m[i]);
    if (!(det > 0.2 * length(m[j]) * length(m[i]))) {
      sliver = true;
      break;
    }
    corner[i] = vec2(c[j] * m[i].y - c[i] * m[j].y, m[j].x * c[i] - m[i].x * c[j]) / det;
  }
  if (sliver) {
    vec2 lo = min(p[0], min(p[1], p[2])) - 1.0, hi = max(p[0], max(p[1], p[2])) + 1.0;
    emit_at(lo);
    emit_at(vec2(hi.x, lo.y));
    emit_at(vec2(lo.x, hi.y));
    emit_at(hi);
  } else {
    emit_at(corner[0]);
    emit_at(corner[1]);
    emit_at(corner[2]);
  }
#else
  emit_at(p[0]);
  emit_at(p[1]);
  emit_at(p[2]);
#endif
  EndPrimitive();
}
