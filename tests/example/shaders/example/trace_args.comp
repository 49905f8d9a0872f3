#version 460
// Test pass "example.trace_args": 64 rays straight down through the scene's BVH from an 8×8
// grid twice the size of the scene's footprint; the hits become the group count of an
// indirect dispatch, and every mark is cleared for the pass that dispatch runs.
#define BVH_SET 0
#define BVH_FIRST_BINDING 2
#include "lib/bvh_traversal.glsl"

layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) writeonly buffer Args { uvec4 args; };
layout(set = 0, binding = 1, std430) writeonly buffer Marks { uint marks[64]; };
layout(push_constant) uniform Push { uint node_count; };

shared uint hits;

void main() {
  uint i = gl_LocalInvocationIndex;
  if (i == 0u) hits = 0u;
  barrier();
  if (node_count > 0u) {
    BvhNode root = bvh_nodes[0];
    vec3 centre = 0.5 * (root.bounds_min + root.bounds_max);
    vec3 extent = root.bounds_max - root.bounds_min;
    // Cell centres at ±(1..15)/16 of the extent: none near the footprint's edges (±1/2).
    vec2 cell = (vec2(i % 8u, i / 8u) + 0.5) / 8.0 * 2.0 - 1.0;
    vec3 o = vec3(centre.x + cell.x * extent.x, root.bounds_max.y + 1.0,
                  centre.z + cell.y * extent.z);
    BvhHit hit = bvh_trace(o, vec3(0.0, -1.0, 0.0), 0.0, 1e30, node_count, true);
    if (hit.hit) atomicAdd(hits, 1u);
  }
  marks[i] = 0u;
  barrier();
  if (i == 0u) args = uvec4(hits, 1u, 1u, 0u);
}
