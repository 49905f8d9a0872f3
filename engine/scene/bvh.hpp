#pragma once
// A bounding volume hierarchy over the world-space triangles of every instance of a scene,
// built on the CPU with binned surface-area heuristic (SAH) splits, for ray tracing (the
// reference path tracer) and CPU ray queries (tests, picking).
//
// Positions are stored relative to `origin()` (the centre of the scene bounds, computed in
// double precision) so that a scene far from the world origin keeps float precision in its
// boxes and triangles; rays given to intersect() are in world space and moved likewise.
//
// Layout: nodes in depth-first order, every child after its parent, the two children of an
// inner node next to each other; a leaf holds a contiguous range of the triangle array.

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <vector>

#include "engine/scene/scene.hpp"

namespace voxgi::scene {

struct BvhNode {
  glm::vec3 bounds_min{0.0f};
  // Inner node: index of the first child (the second is first + 1). Leaf: first triangle.
  uint32_t first = 0;
  glm::vec3 bounds_max{0.0f};
  uint32_t count = 0;  // triangles in a leaf; 0 for an inner node
  bool leaf() const { return count > 0; }
};

// One triangle, in leaf order. Vertices are relative to Bvh::origin().
struct BvhTriangle {
  glm::vec3 v0{0.0f}, v1{0.0f}, v2{0.0f};
  uint32_t instance = 0;  // index into Scene::instances() at build time
  uint32_t index = 0;     // triangle index within the instance's primitive (indices / 3)
};

struct BvhStats {
  uint32_t triangles = 0;
  uint32_t nodes = 0;
  uint32_t leaves = 0;
  uint32_t max_depth = 0;  // the root is depth 0
  // Expected cost of a random ray relative to the root box: sum over inner nodes of
  // area/root_area * traversal cost (1) plus over leaves of area/root_area * triangles *
  // intersection cost (1). Lower is better.
  double sah_cost = 0.0;
  double build_ms = 0.0;  // of the last build (refit_ms for the last refit)
  double refit_ms = 0.0;
};

struct BvhBuildOptions {
  uint32_t bins = 16;           // SAH bins per axis
  uint32_t max_leaf_size = 4;   // a node with more triangles is always split
  float traversal_cost = 1.0f;  // relative to one triangle test
  // Beyond this depth nodes split at the median triangle, so the depth stays below
  // kBvhMaxDepth even for pathological inputs (all centroids in one point).
  uint32_t sah_depth_limit = 40;
};

// Deepest node the builder produces; shader traversal stacks are sized from it.
inline constexpr uint32_t kBvhMaxDepth = 63;

struct BvhHit {
  float t = 0.0f;
  float u = 0.0f;         // barycentric weight of v1
  float v = 0.0f;         // barycentric weight of v2
  uint32_t triangle = 0;  // index into Bvh::triangles()
};

class Bvh {
 public:
  Bvh() = default;
  // Every triangle of every instance (Scene::instances()), transformed by its world matrix.
  // Degenerate triangles are kept (they never report hits); non-finite vertices become 0.
  static Bvh build(const Scene& scene, const BvhBuildOptions& options = {});

  // After Scene::animate(): recomputes the triangles from the instances' new world matrices
  // and every node's bounds bottom-up, keeping the tree (its quality degrades with large
  // motions; rebuild then). The scene must have the structure it was built from; throws
  // SceneError otherwise.
  void refit(const Scene& scene);

  // Closest hit with t in [t_min, t_max] (world-space ray in double, so that far from the
  // world origin it keeps its digits; `direction` need not be unit).
  std::optional<BvhHit> intersect(const glm::dvec3& origin, const glm::vec3& direction, float t_min,
                                  float t_max) const;
  // The same by testing every triangle (for tests and as a definition).
  std::optional<BvhHit> intersect_brute_force(const glm::dvec3& origin, const glm::vec3& direction,
                                              float t_min, float t_max) const;

  const std::vector<BvhNode>& nodes() const { return nodes_; }
  const std::vector<BvhTriangle>& triangles() const { return triangles_; }
  const std::vector<Instance>& instances() const { return instances_; }
  glm::dvec3 origin() const { return origin_; }
  const BvhStats& stats() const { return stats_; }
  bool empty() const { return triangles_.empty(); }

 private:
  void compute_triangles(const Scene& scene);
  void update_stats();

  std::vector<BvhNode> nodes_;
  std::vector<BvhTriangle> triangles_;
  std::vector<Instance> instances_;
  glm::dvec3 origin_{0.0};
  BvhStats stats_;
};

// Ray/triangle test (Möller-Trumbore, both faces). False for degenerate triangles and
// for hits outside [t_min, t_max]; never NaN.
bool intersect_triangle(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& v0,
                        const glm::vec3& v1, const glm::vec3& v2, float t_min, float t_max,
                        float& t, float& u, float& v);

}  // namespace voxgi::scene
