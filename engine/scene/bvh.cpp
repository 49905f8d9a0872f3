#include "engine/scene/bvh.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace voxgi::scene {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

struct Box {
  glm::vec3 min{kInf};
  glm::vec3 max{-kInf};
  void grow(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void grow(const Box& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  bool valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
  float area() const {
    if (!valid()) return 0.0f;
    const glm::vec3 e = max - min;
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

Box triangle_box(const BvhTriangle& t) {
  Box b;
  b.grow(t.v0);
  b.grow(t.v1);
  b.grow(t.v2);
  return b;
}

glm::vec3 finite_or_zero(const glm::dvec3& p) {
  glm::vec3 f(p);
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(f[i])) f[i] = 0.0f;
  }
  return f;
}

const Primitive& instance_primitive(const Scene& scene, const Instance& instance) {
  return scene.meshes[static_cast<size_t>(instance.mesh)]
      .primitives[static_cast<size_t>(instance.primitive)];
}

// World position of a primitive's vertex, in double so that subtracting the origin keeps the
// digits a far-away scene needs.
glm::dvec3 world_position(const glm::dmat4& world, const Primitive& primitive, uint32_t index) {
  const glm::vec3& p = primitive.vertices[index].position;
  return glm::dvec3(world * glm::dvec4(glm::dvec3(p), 1.0));
}

bool valid_index(const Primitive& primitive, uint32_t index) {
  return index < primitive.vertices.size();
}

// Slab test against a node box; returns the entry distance or +inf when missed.
float intersect_box(const glm::vec3& origin, const glm::vec3& inv_dir, const glm::vec3& mn,
                    const glm::vec3& mx, float t_min, float t_max) {
  const glm::vec3 t0 = (mn - origin) * inv_dir;
  const glm::vec3 t1 = (mx - origin) * inv_dir;
  const glm::vec3 near = glm::min(t0, t1);
  const glm::vec3 far = glm::max(t0, t1);
  const float enter = std::max(std::max(near.x, near.y), std::max(near.z, t_min));
  const float exit = std::min(std::min(far.x, far.y), std::min(far.z, t_max));
  return enter <= exit ? enter : kInf;
}

glm::vec3 safe_inverse(const glm::vec3& d) {
  glm::vec3 inv;
  for (int i = 0; i < 3; ++i) {
    // A zero component must give a huge (not infinite) slope so 0 * slope never becomes NaN.
    const float c = std::abs(d[i]) > 1e-20f ? d[i] : std::copysign(1e-20f, d[i]);
    inv[i] = 1.0f / c;
  }
  return inv;
}

class Builder {
 public:
  Builder(const BvhBuildOptions& options, std::vector<BvhTriangle>& triangles,
          std::vector<BvhNode>& nodes)
      : options_(options), triangles_(triangles), nodes_(nodes) {
    boxes_.reserve(triangles.size());
    centroids_.reserve(triangles.size());
    for (const BvhTriangle& t : triangles) {
      boxes_.push_back(triangle_box(t));
      centroids_.push_back((t.v0 + t.v1 + t.v2) * (1.0f / 3.0f));
    }
    order_.resize(triangles.size());
    for (uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;
  }

  void run() {
    if (triangles_.empty()) return;
    nodes_.clear();
    nodes_.reserve(triangles_.size() * 2 / std::max(1u, options_.max_leaf_size) + 1);
    nodes_.push_back({});
    struct Task {
      uint32_t node, begin, end, depth;
    };
    std::vector<Task> stack{{0, 0, static_cast<uint32_t>(triangles_.size()), 0}};
    while (!stack.empty()) {
      const Task task = stack.back();
      stack.pop_back();
      const uint32_t split = split_node(task.node, task.begin, task.end, task.depth);
      if (split == 0) continue;  // leaf
      const uint32_t left = static_cast<uint32_t>(nodes_.size());
      nodes_.push_back({});
      nodes_.push_back({});
      nodes_[task.node].first = left;
      nodes_[task.node].count = 0;
      stack.push_back({left + 1, split, task.end, task.depth + 1});
      stack.push_back({left, task.begin, split, task.depth + 1});
    }
    std::vector<BvhTriangle> reordered;
    reordered.reserve(triangles_.size());
    for (uint32_t i : order_) reordered.push_back(triangles_[i]);
    triangles_ = std::move(reordered);
  }

 private:
  // Sets the node's bounds; makes it a leaf (returns 0) or partitions order_[begin, end) and
  // returns the first index of the right child.
  uint32_t split_node(uint32_t node, uint32_t begin, uint32_t end, uint32_t depth) {
    Box bounds, centroid_bounds;
    for (uint32_t i = begin; i < end; ++i) {
      bounds.grow(boxes_[order_[i]]);
      centroid_bounds.grow(centroids_[order_[i]]);
    }
    BvhNode& n = nodes_[node];
    n.bounds_min = bounds.min;
    n.bounds_max = bounds.max;
    n.first = begin;
    n.count = end - begin;
    const uint32_t count = end - begin;
    if (count <= 1 || depth >= kBvhMaxDepth) return 0;
    if (depth >= options_.sah_depth_limit) {
      return count <= options_.max_leaf_size ? 0 : median_split(begin, end, centroid_bounds);
    }

    const uint32_t bins = std::clamp(options_.bins, 2u, 64u);
    float best_cost = kInf;
    int best_axis = -1;
    uint32_t best_plane = 0;
    const glm::vec3 extent = centroid_bounds.max - centroid_bounds.min;
    std::array<Box, 64> bin_boxes;
    std::array<uint32_t, 64> bin_counts;
    std::array<float, 64> right_area;
    std::array<uint32_t, 64> right_count;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0.0f)) continue;
      const float scale = static_cast<float>(bins) / extent[axis];
      bin_boxes.fill(Box{});
      bin_counts.fill(0);
      for (uint32_t i = begin; i < end; ++i) {
        const uint32_t b =
            bin_of(centroids_[order_[i]][axis], centroid_bounds.min[axis], scale, bins);
        bin_boxes[b].grow(boxes_[order_[i]]);
        ++bin_counts[b];
      }
      Box right;
      uint32_t right_n = 0;
      for (uint32_t b = bins - 1; b > 0; --b) {
        right.grow(bin_boxes[b]);
        right_n += bin_counts[b];
        right_area[b] = right.area();
        right_count[b] = right_n;
      }
      Box left;
      uint32_t left_n = 0;
      for (uint32_t plane = 1; plane < bins; ++plane) {
        left.grow(bin_boxes[plane - 1]);
        left_n += bin_counts[plane - 1];
        if (left_n == 0 || right_count[plane] == 0) continue;
        const float cost = left.area() * static_cast<float>(left_n) +
                           right_area[plane] * static_cast<float>(right_count[plane]);
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_plane = plane;
        }
      }
    }

    if (best_axis < 0) {
      // Every centroid in one point: no plane separates them.
      return count <= options_.max_leaf_size ? 0 : median_split(begin, end, centroid_bounds);
    }
    const float area = bounds.area();
    const float leaf_cost = static_cast<float>(count);
    const float split_cost = area > 0.0f ? options_.traversal_cost + best_cost / area
                                         : options_.traversal_cost + leaf_cost;
    if (split_cost >= leaf_cost && count <= options_.max_leaf_size) return 0;

    const float scale = static_cast<float>(bins) / extent[best_axis];
    const float lo = centroid_bounds.min[best_axis];
    const auto middle = std::partition(
        order_.begin() + begin, order_.begin() + end,
        [&](uint32_t t) { return bin_of(centroids_[t][best_axis], lo, scale, bins) < best_plane; });
    const uint32_t split = static_cast<uint32_t>(middle - order_.begin());
    if (split == begin || split == end) return median_split(begin, end, centroid_bounds);
    return split;
  }

  static uint32_t bin_of(float c, float lo, float scale, uint32_t bins) {
    const float f = (c - lo) * scale;
    if (!(f > 0.0f)) return 0;
    return std::min(static_cast<uint32_t>(f), bins - 1);
  }

  uint32_t median_split(uint32_t begin, uint32_t end, const Box& centroid_bounds) {
    const glm::vec3 e = centroid_bounds.max - centroid_bounds.min;
    const int axis = (e.x >= e.y && e.x >= e.z) ? 0 : (e.y >= e.z ? 1 : 2);
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(
        order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
        [&](uint32_t a, uint32_t b) { return centroids_[a][axis] < centroids_[b][axis]; });
    return mid;
  }

  const BvhBuildOptions& options_;
  std::vector<BvhTriangle>& triangles_;
  std::vector<BvhNode>& nodes_;
  std::vector<Box> boxes_;
  std::vector<glm::vec3> centroids_;
  std::vector<uint32_t> order_;
};

double elapsed_ms(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

bool intersect_triangle(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& v0,
                        const glm::vec3& v1, const glm::vec3& v2, float t_min, float t_max,
                        float& t, float& u, float& v) {
  const glm::vec3 e1 = v1 - v0;
  const glm::vec3 e2 = v2 - v0;
  const glm::vec3 p = glm::cross(direction, e2);
  const float det = glm::dot(e1, p);
  // Relative threshold: zero-area triangles and rays in the triangle's plane never hit.
  const float scale = glm::length(e1) * glm::length(e2) * glm::length(direction);
  if (!(std::abs(det) > 1e-12f * scale) || !(scale > 0.0f)) return false;
  const float inv_det = 1.0f / det;
  const glm::vec3 s = origin - v0;
  u = glm::dot(s, p) * inv_det;
  if (!(u >= 0.0f && u <= 1.0f)) return false;
  const glm::vec3 q = glm::cross(s, e1);
  v = glm::dot(direction, q) * inv_det;
  if (!(v >= 0.0f && u + v <= 1.0f)) return false;
  t = glm::dot(e2, q) * inv_det;
  return t >= t_min && t <= t_max;
}

void Bvh::compute_triangles(const Scene& scene) {
  for (BvhTriangle& tri : triangles_) {
    const Instance& instance = instances_[tri.instance];
    const Primitive& primitive = instance_primitive(scene, instance);
    const glm::dmat4 world(instances_[tri.instance].world);
    glm::vec3* corners[3] = {&tri.v0, &tri.v1, &tri.v2};
    for (uint32_t k = 0; k < 3; ++k) {
      const uint32_t index = primitive.indices[tri.index * 3 + k];
      *corners[k] = valid_index(primitive, index)
                        ? finite_or_zero(world_position(world, primitive, index) - origin_)
                        : glm::vec3(0.0f);
    }
  }
}

Bvh Bvh::build(const Scene& scene, const BvhBuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  Bvh bvh;
  bvh.instances_ = scene.instances();

  // The origin: centre of the world bounds, in double.
  glm::dvec3 mn(std::numeric_limits<double>::infinity());
  glm::dvec3 mx(-std::numeric_limits<double>::infinity());
  for (uint32_t i = 0; i < bvh.instances_.size(); ++i) {
    const Instance& instance = bvh.instances_[i];
    const Primitive& primitive = instance_primitive(scene, instance);
    const glm::dmat4 world(instance.world);
    for (uint32_t v = 0; v < primitive.vertices.size(); ++v) {
      const glm::dvec3 p = world_position(world, primitive, v);
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
      mn = glm::min(mn, p);
      mx = glm::max(mx, p);
    }
    const uint32_t triangle_count = static_cast<uint32_t>(primitive.indices.size() / 3);
    for (uint32_t t = 0; t < triangle_count; ++t) bvh.triangles_.push_back({{}, {}, {}, i, t});
  }
  bvh.origin_ = mn.x <= mx.x ? (mn + mx) * 0.5 : glm::dvec3(0.0);
  bvh.compute_triangles(scene);

  Builder(options, bvh.triangles_, bvh.nodes_).run();
  bvh.update_stats();
  bvh.stats_.build_ms = elapsed_ms(start);
  return bvh;
}

void Bvh::refit(const Scene& scene) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Instance> current = scene.instances();
  bool same = current.size() == instances_.size();
  for (size_t i = 0; same && i < current.size(); ++i) {
    same = current[i].mesh == instances_[i].mesh && current[i].primitive == instances_[i].primitive;
  }
  if (!same) {
    throw SceneError(scene.source +
                     ": BVH refit: the scene's instances differ from the ones "
                     "the BVH was built from (rebuild it)");
  }
  instances_ = std::move(current);
  compute_triangles(scene);
  for (size_t i = nodes_.size(); i-- > 0;) {
    BvhNode& n = nodes_[i];
    Box b;
    if (n.leaf()) {
      for (uint32_t t = n.first; t < n.first + n.count; ++t) b.grow(triangle_box(triangles_[t]));
    } else {
      b.grow(Box{nodes_[n.first].bounds_min, nodes_[n.first].bounds_max});
      b.grow(Box{nodes_[n.first + 1].bounds_min, nodes_[n.first + 1].bounds_max});
    }
    n.bounds_min = b.min;
    n.bounds_max = b.max;
  }
  update_stats();
  stats_.refit_ms = elapsed_ms(start);
}

void Bvh::update_stats() {
  const double build_ms = stats_.build_ms;
  stats_ = {};
  stats_.build_ms = build_ms;
  stats_.triangles = static_cast<uint32_t>(triangles_.size());
  stats_.nodes = static_cast<uint32_t>(nodes_.size());
  if (nodes_.empty()) return;
  const double root_area = Box{nodes_[0].bounds_min, nodes_[0].bounds_max}.area();
  std::vector<uint32_t> depth(nodes_.size(), 0);
  for (size_t i = 0; i < nodes_.size(); ++i) {
    const BvhNode& n = nodes_[i];
    const double area = Box{n.bounds_min, n.bounds_max}.area();
    const double ratio = root_area > 0.0 ? area / root_area : 1.0;
    stats_.max_depth = std::max(stats_.max_depth, depth[i]);
    if (n.leaf()) {
      ++stats_.leaves;
      stats_.sah_cost += ratio * n.count;
    } else {
      stats_.sah_cost += ratio * 1.0;
      depth[n.first] = depth[n.first + 1] = depth[i] + 1;
    }
  }
}

std::optional<BvhHit> Bvh::intersect(const glm::dvec3& world_origin, const glm::vec3& direction,
                                     float t_min, float t_max) const {
  if (nodes_.empty()) return std::nullopt;
  const glm::vec3 origin(world_origin - origin_);
  const glm::vec3 inv_dir = safe_inverse(direction);
  std::optional<BvhHit> best;
  float closest = t_max;
  std::array<uint32_t, kBvhMaxDepth + 2> stack;
  uint32_t top = 0;
  if (intersect_box(origin, inv_dir, nodes_[0].bounds_min, nodes_[0].bounds_max, t_min, closest) ==
      kInf) {
    return std::nullopt;
  }
  stack[top++] = 0;
  while (top > 0) {
    const BvhNode& n = nodes_[stack[--top]];
    if (n.leaf()) {
      for (uint32_t i = n.first; i < n.first + n.count; ++i) {
        const BvhTriangle& tri = triangles_[i];
        float t, u, v;
        if (intersect_triangle(origin, direction, tri.v0, tri.v1, tri.v2, t_min, closest, t, u,
                               v)) {
          closest = t;
          best = BvhHit{t, u, v, i};
        }
      }
      continue;
    }
    const BvhNode& a = nodes_[n.first];
    const BvhNode& b = nodes_[n.first + 1];
    const float ta = intersect_box(origin, inv_dir, a.bounds_min, a.bounds_max, t_min, closest);
    const float tb = intersect_box(origin, inv_dir, b.bounds_min, b.bounds_max, t_min, closest);
    // Push the farther child first so the nearer one is visited first.
    if (ta <= tb) {
      if (tb != kInf) stack[top++] = n.first + 1;
      if (ta != kInf) stack[top++] = n.first;
    } else {
      if (ta != kInf) stack[top++] = n.first;
      if (tb != kInf) stack[top++] = n.first + 1;
    }
  }
  return best;
}

std::optional<BvhHit> Bvh::intersect_brute_force(const glm::dvec3& world_origin,
                                                 const glm::vec3& direction, float t_min,
                                                 float t_max) const {
  const glm::vec3 origin(world_origin - origin_);
  std::optional<BvhHit> best;
  float closest = t_max;
  for (uint32_t i = 0; i < triangles_.size(); ++i) {
    const BvhTriangle& tri = triangles_[i];
    float t, u, v;
    if (intersect_triangle(origin, direction, tri.v0, tri.v1, tri.v2, t_min, closest, t, u, v)) {
      closest = t;
      best = BvhHit{t, u, v, i};
    }
  }
  return best;
}

}  // namespace voxgi::scene
