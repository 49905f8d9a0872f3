#ifndef VOXGI_BVH_TRAVERSAL_GLSL
#define VOXGI_BVH_TRAVERSAL_GLSL
// Ray traversal of the BVH that voxgi::scene::GpuBvh uploads (engine/scene/gpu_bvh.hpp; the
// structs mirror GpuBvhNode, GpuBvhTriangle, GpuBvhShading and GpuEmitter). Positions are
// relative to the BVH origin: subtract it from world-space ray origins.
//
// Before including, a shader may define
//   BVH_SET, BVH_FIRST_BINDING  where the four buffers go (default set 0, bindings 0..3:
//                               nodes, triangles, shading, emitters);
//   BVH_HIT_FILTER              and a function `bool bvh_hit_filter(uint triangle, float u,
//                               float v)` declared before this file: false lets the ray pass
//                               through that hit (alpha masks, stochastic transparency).

#ifndef BVH_SET
#define BVH_SET 0
#endif
#ifndef BVH_FIRST_BINDING
#define BVH_FIRST_BINDING 0
#endif

// Deepest node (voxgi::scene::kBvhMaxDepth) + 2: the nearest-first stack never holds more.
#define BVH_STACK_SIZE 65

struct BvhNode {
  vec3 bounds_min;
  uint first;  // inner: first child (the second follows); leaf: first triangle
  vec3 bounds_max;
  uint count;  // 0: inner node
};

struct BvhTriangle {
  vec4 v0;  // w: +1, or -1 where the glTF front is -cross(v1 - v0, v2 - v0) (mirrored)
  vec4 v1;
  vec4 v2;
};

struct BvhShading {
  vec4 normal[3];   // world space, not normalised
  vec4 tangent[3];  // xyz world, w bitangent sign
  vec4 uv01;
  vec2 uv2;
  uint material;
  float emitter_pdf_area;  // light-sampling density per unit area; 0: not an emitter
  vec4 uv1_01;    // TEXCOORD_1 of vertex 0 (xy) and 1 (zw)
  vec4 uv1_2;     // xy: TEXCOORD_1 of vertex 2
  vec4 color[3];  // COLOR_0 per vertex
};

struct BvhEmitter {
  uint triangle;
  float cdf;
};

layout(set = BVH_SET, binding = BVH_FIRST_BINDING, std430) readonly buffer BvhNodes {
  BvhNode bvh_nodes[];
};
layout(set = BVH_SET, binding = BVH_FIRST_BINDING + 1, std430) readonly buffer BvhTriangles {
  BvhTriangle bvh_triangles[];
};
layout(set = BVH_SET, binding = BVH_FIRST_BINDING + 2, std430) readonly buffer BvhShadings {
  BvhShading bvh_shading[];
};
layout(set = BVH_SET, binding = BVH_FIRST_BINDING + 3, std430) readonly buffer BvhEmitters {
  BvhEmitter bvh_emitters[];
};

struct BvhHit {
  bool hit;
  float t;
  float u;  // barycentric weight of v1
  float v;  // barycentric weight of v2
  uint triangle;
};

// Möller-Trumbore, both faces; false for degenerate triangles and rays in their plane.
bool bvh_intersect_triangle(vec3 o, vec3 d, BvhTriangle tri, float t_min, float t_max,
                            out float t, out float u, out float v) {
  t = 0.0;
  u = 0.0;
  v = 0.0;
  vec3 e1 = tri.v1.xyz - tri.v0.xyz;
  vec3 e2 = tri.v2.xyz - tri.v0.xyz;
  vec3 p = cross(d, e2);
  float det = dot(e1, p);
  float scale = length(e1) * length(e2) * length(d);
  if (!(abs(det) > 1e-12 * scale) || !(scale > 0.0)) return false;
  float inv_det = 1.0 / det;
  vec3 s = o - tri.v0.xyz;
  u = dot(s, p) * inv_det;
  if (!(u >= 0.0 && u <= 1.0)) return false;
  vec3 q = cross(s, e1);
  v = dot(d, q) * inv_det;
  if (!(v >= 0.0 && u + v <= 1.0)) return false;
  t = dot(e2, q) * inv_det;
  return t >= t_min && t <= t_max;
}

// Entry distance into a node's box, or -1 when the ray misses it within [t_min, t_max].
float bvh_intersect_box(vec3 o, vec3 inv_d, BvhNode node, float t_min, float t_max) {
  vec3 t0 = (node.bounds_min - o) * inv_d;
  vec3 t1 = (node.bounds_max - o) * inv_d;
  vec3 near = min(t0, t1);
  vec3 far = max(t0, t1);
  float enter = max(max(near.x, near.y), max(near.z, t_min));
  float exit = min(min(far.x, far.y), min(far.z, t_max));
  return enter <= exit ? enter : -1.0;
}

vec3 bvh_safe_inverse(vec3 d) {
  // A zero component gets a huge finite slope so that 0 * slope never turns into NaN.
  vec3 s = mix(vec3(1.0), vec3(-1.0), lessThan(d, vec3(0.0)));
  return 1.0 / mix(d, s * 1e-20, lessThan(abs(d), vec3(1e-20)));
}

bool bvh_accept(uint triangle, float u, float v) {
#ifdef BVH_HIT_FILTER
  return bvh_hit_filter(triangle, u, v);
#else
  return true;
#endif
}

// Closest hit along o + t d, t in [t_min, t_max]. node_count 0: nothing to hit.
// any_hit: stop at the first accepted hit (shadow rays).
BvhHit bvh_trace(vec3 o, vec3 d, float t_min, float t_max, uint node_count, bool any_hit) {
  BvhHit result;
  result.hit = false;
  result.t = t_max;
  result.u = 0.0;
  result.v = 0.0;
  result.triangle = 0u;
  if (node_count == 0u) return result;
  vec3 inv_d = bvh_safe_inverse(d);
  uint stack[BVH_STACK_SIZE];
  int top = 0;
  if (bvh_intersect_box(o, inv_d, bvh_nodes[0], t_min, t_max) < 0.0) return result;
  stack[top++] = 0u;
  while (top > 0) {
    BvhNode node = bvh_nodes[stack[--top]];
    if (node.count > 0u) {
      for (uint i = node.first; i < node.first + node.count; ++i) {
        float t, u, v;
        if (bvh_intersect_triangle(o, d, bvh_triangles[i], t_min, result.t, t, u, v) &&
            bvh_accept(i, u, v)) {
          result.hit = true;
          result.t = t;
          result.u = u;
          result.v = v;
          result.triangle = i;
          if (any_hit) return result;
        }
      }
      continue;
    }
    float ta = bvh_intersect_box(o, inv_d, bvh_nodes[node.first], t_min, result.t);
    float tb = bvh_intersect_box(o, inv_d, bvh_nodes[node.first + 1u], t_min, result.t);
    // The nearer child goes on top of the stack so it is visited first.
    uint near_child = ta <= tb ? node.first : node.first + 1u;
    uint far_child = ta <= tb ? node.first + 1u : node.first;
    float t_near = min(ta, tb);
    float t_far = max(ta, tb);
    if (t_near < 0.0) {
      // At most one child was hit: it is the one with the larger entry distance.
      if (t_far >= 0.0 && top < BVH_STACK_SIZE) stack[top++] = far_child;
      continue;
    }
    if (top + 2 > BVH_STACK_SIZE) continue;  // cannot happen for depths <= kBvhMaxDepth
    stack[top++] = far_child;
    stack[top++] = near_child;
  }
  return result;
}

// Geometric normal (unnormalised, from the winding) of a BVH triangle.
vec3 bvh_triangle_normal(uint triangle) {
  BvhTriangle tri = bvh_triangles[triangle];
  return cross(tri.v1.xyz - tri.v0.xyz, tri.v2.xyz - tri.v0.xyz);
}

// The geometric normal on the glTF front's side (the counter-clockwise winding's, clockwise
// under a mirroring transform), as the rasteriser culls; not normalised.
vec3 bvh_triangle_front_normal(uint triangle) {
  return bvh_triangles[triangle].v0.w < 0.0 ? -bvh_triangle_normal(triangle)
                                            : bvh_triangle_normal(triangle);
}

#endif
