#pragma once
// What the lpv passes share: the formats of the reflective shadow maps, the layout of the LPV
// buffers (GLSL twin: shaders/lpv/cells.glsl) and the slots and size rules built on them.
//
// The LPV has one cell per voxel of each level of the voxel clipmap it is bound with (one
// level: a single volume fitted to the scene; several: cascades that follow the camera,
// snapped to their cell as the clipmap's windows are). A clipmap of L levels gives 2 L - 1
// volumes (cascades): the L levels with the light of all sources in their window, then levels
// 1 .. L - 1 with only the sources outside the next finer window. Cells are counted in window
// order, cascade by cascade: cell = ((cascade * R + z) * R + y) * R + x.
//
// The octree LPV (seed 002 sec. 4.2) adds, per cascade, the levels R/2, R/4, ... after those
// cells: octree level o has (R >> o)^3 cells per cascade, counted the same way from the end of
// level o - 1. One octree level is the uniform LPV.

#include <vulkan/vulkan.h>

#include <cstdint>

#include "engine/graph/pass.hpp"

namespace voxgi::passes::lpv {

inline constexpr VkFormat kRsmFluxFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kRsmNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kRsmPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

// Per cell and colour channel, four two-band SH coefficients (shaders/lpv/sh.glsl).
inline constexpr uint32_t kCoefficientsPerCell = 12;

// The most octree levels a pass accepts (R = 128 down to 1).
inline constexpr uint32_t kMaxOctreeLevels = 8;

// The LPV's buffers (shaders/lpv/cells.glsl):
//   Injected  lpv.inject's fixed-point sums: a 16-byte header (the largest contribution's
//             magnitude as float bits, the number of contributions that may add up in one
//             cell), then kCoefficientsPerCell int32 per cell of octree level 0
//   Levels    a cell record per cell of every octree level (five vec4, LPV_RECORD_VEC4S: SH
//             per channel, stopped flux and index mark, geometry): lpv.downsample's injected
//             levels and lpv.propagate's accumulated levels
//   Work      lpv.propagate's scratch: two SH states per cell of every octree level (three
//             vec4 per cell each)
//   Radiance  lpv.merge's result: a cell record per cell of octree level 0
enum class LpvBuffer { Injected, Levels, Work, Radiance };
VkDeviceSize lpv_buffer_bytes(LpvBuffer buffer, uint64_t cells);

// The level-0 cells of every cascade over a clipmap of L levels: R^3 x (2 L - 1) (the L levels'
// volumes of all light sources, then L - 1 of the sources outside the next finer window); 0
// for anything but a clipmap.
uint64_t lpv_cell_count(const graph::ResourceInfo& clipmap);
// The cells of `octree_levels` octree levels of every cascade (lpv_cell_count's at 1).
uint64_t lpv_octree_cell_count(const graph::ResourceInfo& clipmap, uint32_t octree_levels);
// The clipmap's voxels, R^3 x L.
uint64_t lpv_voxel_count(const graph::ResourceInfo& clipmap);

// The size rule of an LPV buffer over the clipmap bound to `clipmap_slot` (with the pass's
// "octree_levels" parameter for Levels and Work), and the validate check that reports `slot`
// when its buffer is smaller.
graph::SizeRule lpv_buffer_size(LpvBuffer buffer, const char* clipmap_slot);
void check_lpv_buffer(graph::PassCheck& check, LpvBuffer buffer, const char* slot,
                      const char* clipmap_slot);

// The "octree_levels" parameter and its check against the clipmap's resolution (each level
// halves it: R must be divisible by 2^(levels - 1)).
graph::ParamSpec octree_levels_param();
void check_octree_levels(graph::PassCheck& check, const char* clipmap_slot);

// The "merge" parameter of lpv.propagate and lpv.merge: how the octree levels combine.
graph::ParamSpec merge_param();

}  // namespace voxgi::passes::lpv
