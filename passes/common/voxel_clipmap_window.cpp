#include "passes/common/voxel_clipmap_window.hpp"

#include <algorithm>
#include <cmath>

namespace voxgi::passes::common {

double auto_voxel_size(double scene_extent, uint32_t resolution, uint32_t levels, double reach) {
  const double extent = std::isfinite(scene_extent) && scene_extent > 1e-9 ? scene_extent : 1.0;
  const double r = static_cast<double>(resolution);
  // Voxels of the coarsest level surely inside its window on each side of the centre: R/2,
  // less one the window snapping may take and one that consumers keep as a margin.
  const double sure = std::max(1.0, r / 2.0 - 2.0);
  const double for_reach = std::isfinite(reach) && reach > 0.0 ? reach / sure : 0.0;
  if (levels <= 1) return std::max(extent / std::max(1.0, r - 4.0), for_reach);
  const double coarsest = std::max(extent / sure, for_reach);
  return coarsest / std::ldexp(1.0, static_cast<int>(levels) - 1);
}

double window_reach(const glm::dvec3& center, const glm::dvec3& scene_min,
                    const glm::dvec3& scene_max) {
  const glm::dvec3 far = glm::max(glm::abs(center - scene_min), glm::abs(scene_max - center));
  const double reach = std::max({far.x, far.y, far.z});
  return std::isfinite(reach) ? reach : 0.0;
}

namespace {

// Bounds that hold something and are finite (an empty scene's are +inf / -inf).
bool finite_bounds(const glm::dvec3& scene_min, const glm::dvec3& scene_max) {
  return glm::all(glm::lessThanEqual(scene_min, scene_max)) &&
         glm::all(glm::lessThan(glm::abs(scene_min), glm::dvec3(1e300))) &&
         glm::all(glm::lessThan(glm::abs(scene_max), glm::dvec3(1e300)));
}

}  // namespace

glm::dvec3 window_center_in_scene(const glm::dvec3& camera, const glm::dvec3& scene_min,
                                  const glm::dvec3& scene_max) {
  return finite_bounds(scene_min, scene_max) ? glm::clamp(camera, scene_min, scene_max) : camera;
}

glm::dvec3 level_window_center(const glm::dvec3& center, const glm::dvec3& scene_min,
                               const glm::dvec3& scene_max, double half_width) {
  if (!finite_bounds(scene_min, scene_max) || !(half_width >= 0.0) || !std::isfinite(half_width)) {
    return center;
  }
  glm::dvec3 out = center;
  for (int a = 0; a < 3; ++a) {
    const double lo = scene_min[a] + half_width;
    const double hi = scene_max[a] - half_width;
    out[a] = lo <= hi ? std::clamp(center[a], lo, hi) : 0.5 * (scene_min[a] + scene_max[a]);
  }
  return out;
}

void nest_window_origins(std::vector<glm::ivec3>& origins, uint32_t resolution, int margin) {
  const int r = static_cast<int>(resolution);
  margin = std::clamp(margin - margin % 2, 0, r / 4);
  for (size_t l = origins.size(); l-- > 1;) {
    const glm::ivec3 coarse = origins[l];
    const glm::ivec3 lo = coarse * 2 + glm::ivec3(margin);
    const glm::ivec3 hi = (coarse + glm::ivec3(r)) * 2 - glm::ivec3(margin + r);
    origins[l - 1] = glm::clamp(origins[l - 1], lo, hi);
  }
}

glm::dvec3 snap_anchor(const glm::dvec3& point, double coarsest_voxel_size) {
  const double cell = 2.0 * coarsest_voxel_size;
  return glm::floor(point / cell + 0.5) * cell;
}

glm::dvec3 fixed_window_anchor(const glm::dvec3& point, double coarsest_voxel_size,
                               uint32_t resolution) {
  return snap_anchor(point, coarsest_voxel_size) -
         glm::dvec3(0.5 * static_cast<double>(resolution) * coarsest_voxel_size);
}

glm::ivec3 window_origin(const glm::dvec3& center_relative, double voxel_size,
                         uint32_t resolution) {
  const glm::dvec3 pairs = glm::floor(center_relative / (2.0 * voxel_size) + 0.5);
  // Far beyond any sane window: the caller re-anchors before this can overflow.
  const glm::dvec3 clamped = glm::clamp(pairs, glm::dvec3(-(1 << 29)), glm::dvec3(1 << 29));
  return glm::ivec3(clamped) * 2 - glm::ivec3(static_cast<int>(resolution / 2));
}

std::vector<VoxelBox> exposed_slabs(int level, const glm::ivec3& old_origin,
                                    const glm::ivec3& new_origin, uint32_t resolution) {
  const int r = static_cast<int>(resolution);
  const glm::ivec3 d = new_origin - old_origin;
  std::vector<VoxelBox> boxes;
  if (std::abs(d.x) >= r || std::abs(d.y) >= r || std::abs(d.z) >= r) {
    boxes.push_back({level, glm::ivec3(0), glm::ivec3(r)});
    return boxes;
  }
  // Per axis: the entering range and the range kept from the old window.
  glm::ivec3 enter_min(0), enter_max(0), kept_min(0), kept_max(r);
  for (int a = 0; a < 3; ++a) {
    if (d[a] > 0) {
      enter_min[a] = r - d[a];
      enter_max[a] = r;
      kept_max[a] = r - d[a];
    } else if (d[a] < 0) {
      enter_min[a] = 0;
      enter_max[a] = -d[a];
      kept_min[a] = -d[a];
    }
  }
  // Disjoint: the x slab spans y and z; the y slab only the kept x; the z slab kept x and y.
  glm::ivec3 lo(0), hi(r);
  for (int a = 0; a < 3; ++a) {
    if (d[a] != 0) {
      VoxelBox box{level, lo, hi};
      box.min[a] = enter_min[a];
      box.max[a] = enter_max[a];
      if (!box.empty()) boxes.push_back(box);
    }
    lo[a] = kept_min[a];
    hi[a] = kept_max[a];
  }
  return boxes;
}

VoxelBox window_box(int level, const WorldBox& box, const glm::dvec3& anchor,
                    const glm::ivec3& origin, double voxel_size, uint32_t resolution, int margin) {
  const glm::dvec3 lo = (box.min - anchor) / voxel_size - glm::dvec3(origin);
  const glm::dvec3 hi = (box.max - anchor) / voxel_size - glm::dvec3(origin);
  const double r = static_cast<double>(resolution);
  VoxelBox out{level, glm::ivec3(0), glm::ivec3(0)};
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(lo[a]) || !std::isfinite(hi[a])) return out;
    const double mn = std::clamp(std::floor(lo[a]) - margin, 0.0, r);
    const double mx = std::clamp(std::floor(hi[a]) + 1.0 + margin, 0.0, r);
    out.min[a] = static_cast<int>(mn);
    out.max[a] = static_cast<int>(mx);
  }
  return out;
}

std::vector<VoxelBox> split_box(const VoxelBox& box, int64_t max_voxels) {
  std::vector<VoxelBox> out;
  if (box.empty()) return out;
  const glm::ivec3 ext = box.max - box.min;
  const int64_t slice = int64_t(ext.x) * ext.y;
  if (slice <= max_voxels) {
    const int depth = static_cast<int>(std::max<int64_t>(1, max_voxels / slice));
    for (int z = box.min.z; z < box.max.z; z += depth) {
      VoxelBox piece = box;
      piece.min.z = z;
      piece.max.z = std::min(box.max.z, z + depth);
      out.push_back(piece);
    }
    return out;
  }
  const int rows = static_cast<int>(std::max<int64_t>(1, max_voxels / ext.x));
  for (int z = box.min.z; z < box.max.z; ++z) {
    for (int y = box.min.y; y < box.max.y; y += rows) {
      VoxelBox piece = box;
      piece.min.z = z;
      piece.max.z = z + 1;
      piece.min.y = y;
      piece.max.y = std::min(box.max.y, y + rows);
      out.push_back(piece);
    }
  }
  return out;
}

std::vector<VoxelBox> merge_overlapping(std::vector<VoxelBox> boxes) {
  boxes.erase(
      std::remove_if(boxes.begin(), boxes.end(), [](const VoxelBox& b) { return b.empty(); }),
      boxes.end());
  bool merged = true;
  while (merged) {
    merged = false;
    for (size_t i = 0; i < boxes.size() && !merged; ++i) {
      for (size_t j = i + 1; j < boxes.size() && !merged; ++j) {
        const VoxelBox& a = boxes[i];
        const VoxelBox& b = boxes[j];
        if (a.level != b.level) continue;
        if (glm::any(glm::greaterThanEqual(a.min, b.max)) ||
            glm::any(glm::greaterThanEqual(b.min, a.max))) {
          continue;
        }
        boxes[i] = {a.level, glm::min(a.min, b.min), glm::max(a.max, b.max)};
        boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(j));
        merged = true;
      }
    }
  }
  return boxes;
}

WorldBox transform_box(const glm::vec3& min, const glm::vec3& max, const glm::mat4& world) {
  const glm::dmat4 m(world);
  WorldBox out{glm::dvec3(INFINITY), glm::dvec3(-INFINITY)};
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p((corner & 1) ? max.x : min.x, (corner & 2) ? max.y : min.y,
                       (corner & 4) ? max.z : min.z);
    const glm::dvec3 w = glm::dvec3(m * glm::dvec4(p, 1.0));
    out.min = glm::min(out.min, w);
    out.max = glm::max(out.max, w);
  }
  return out;
}

}  // namespace voxgi::passes::common
