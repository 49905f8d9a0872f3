#pragma once
// CPU side of the voxel clipmap: where each level's window lies, which boxes of voxels must be
// revoxelized when windows move or dynamic geometry moves. What it tells consumers, the
// `VoxelClipmapInfo` buffer, is a contract (passes/contracts/voxel_clipmap.hpp). Plain math, no
// Vulkan.

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace voxgi::passes::common {

// A box of voxels of one level in window coordinates (0..R-1), max exclusive.
struct VoxelBox {
  int level = 0;
  glm::ivec3 min{0};
  glm::ivec3 max{0};
  bool empty() const { return max.x <= min.x || max.y <= min.y || max.z <= min.z; }
  int64_t voxels() const {
    return empty() ? 0 : int64_t(max.x - min.x) * (max.y - min.y) * (max.z - min.z);
  }
};

// World-space axis-aligned box, double precision (scenes far from the origin).
struct WorldBox {
  glm::dvec3 min{0.0};
  glm::dvec3 max{0.0};
};

// Level-0 voxel edge chosen when the parameter is 0. With one level the window is fitted to
// the scene: R - 4 voxels span the largest scene side (two voxels of margin each side, one of
// which the window snapping may take). With L levels the coarsest level's half-width spans the
// largest side: windows that follow the camera centre on a point inside the scene bounds
// (window_center_in_scene), so the whole scene then stays inside the coarsest level wherever
// the camera goes. Either way the coarsest level is made large enough that R/2 - 2 of its
// voxels (what is left on each side of the window centre after the snapping and the consumers'
// one-voxel margin) span `reach`, the distance from the first window centre to the farthest
// scene-bounds face (window_reach). Empty scenes (and single points) use a 1 m side.
double auto_voxel_size(double scene_extent, uint32_t resolution, uint32_t levels,
                       double reach = 0.0);

// The largest per-axis distance from `center` to the far face of the box [scene_min,
// scene_max]: the half-width a window centred there needs to contain the box (0 if not finite).
double window_reach(const glm::dvec3& center, const glm::dvec3& scene_min,
                    const glm::dvec3& scene_max);

// Where windows that follow the camera centre: the camera clamped into the scene bounds. A
// level's window centred there holds every scene point that the same window centred on the
// camera would hold (per axis, a point inside the bounds is no farther from the clamped centre
// than from the camera), so a camera outside the scene no longer spends its finest levels on
// empty space in front of it. The camera itself where the bounds are empty or not finite.
glm::dvec3 window_center_in_scene(const glm::dvec3& camera, const glm::dvec3& scene_min,
                                  const glm::dvec3& scene_max);

// Where one level's window centres when windows follow the camera: `center`
// (window_center_in_scene) moved, per axis, as far into the scene bounds as the window's
// `half_width` allows, so that a window narrower than the scene on an axis spends none of its
// voxels beyond the bounds there, and a wider one centres on the scene. From a camera outside
// the scene the finest levels still hold the side it faces, and each coarser level as much of
// the scene as it can: a level as wide as the scene then holds all of it, at its resolution,
// where a window centred on the bounds' face would hold only its near half. `center` itself
// where the bounds are empty or not finite.
glm::dvec3 level_window_center(const glm::dvec3& center, const glm::dvec3& scene_min,
                               const glm::dvec3& scene_max, double half_width);

// Moves each level's window origin (voxels of its level, from the anchor; coarsest last) inside
// the next coarser window with `margin` voxels of the finer level to spare on every side (an
// even number, at most R / 4), coarsest first. Windows centred on different points must stay
// nested: consumers replace a coarse voxel by the finer level wherever that level's window
// holds it, and sample a coarser level around any point of a finer window, two of its voxels
// from its edge at least (a trilinear footprint never wraps around its storage).
void nest_window_origins(std::vector<glm::ivec3>& origins, uint32_t resolution, int margin);

// The anchor: `point` snapped to the grid of twice the coarsest voxel edge, so that every
// level's window corner (an even number of its voxels from the anchor) lies on every coarser
// level's grid and the levels stay nested.
glm::dvec3 snap_anchor(const glm::dvec3& point, double coarsest_voxel_size);

// The anchor of windows that stay put (one level fitted to the scene, or windows centred on
// it): snap_anchor's moved R/2 coarsest voxels towards -x, -y, -z, so that the coarsest window
// centred on `point` starts at voxel index 0 (window_origin), a multiple of R. Its toroidal
// storage is then the identity, its faces are the texture's, and cone tracers read beyond it
// as empty (shaders/contracts/cone_trace.glsl). The voxel grid and the windows do not move.
glm::dvec3 fixed_window_anchor(const glm::dvec3& point, double coarsest_voxel_size,
                               uint32_t resolution);

// Window min corner (voxels of the level, from the anchor) of a window of R voxels centred on
// `center_relative` (metres from the anchor): an even voxel count, so windows are nested.
glm::ivec3 window_origin(const glm::dvec3& center_relative, double voxel_size, uint32_t resolution);

// The voxels that enter a level's window when its origin moves from `old_origin` to
// `new_origin`: up to three disjoint slabs, or the whole window when it moved by R or more on
// an axis.
std::vector<VoxelBox> exposed_slabs(int level, const glm::ivec3& old_origin,
                                    const glm::ivec3& new_origin, uint32_t resolution);

// The voxels of a level's window (origin, edge) that `box` touches, grown by `margin` voxels and
// clipped to the window; empty when outside.
VoxelBox window_box(int level, const WorldBox& box, const glm::dvec3& anchor,
                    const glm::ivec3& origin, double voxel_size, uint32_t resolution, int margin);

// Splits a box along z (then y) into pieces of at most `max_voxels` voxels (>= one row).
std::vector<VoxelBox> split_box(const VoxelBox& box, int64_t max_voxels);

// Merges boxes of the same level that overlap, until none do.
std::vector<VoxelBox> merge_overlapping(std::vector<VoxelBox> boxes);

// World bounds of an object-space box under a transform.
WorldBox transform_box(const glm::vec3& min, const glm::vec3& max, const glm::mat4& world);

}  // namespace voxgi::passes::common
