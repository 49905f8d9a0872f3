#pragma once
// What the lpv passes share: the formats of the reflective shadow maps, the layout of the LPV
// buffers (GLSL twin: shaders/lpv/cells.glsl) and the slots and size rules built on them.
//
// The LPV has one cell per voxel of each level of the voxel clipmap it is bound with (one
// level: a single volume fitted to the scene; several: cascades that follow the camera,
// snapped to their cell as the clipmap's windows are). Cells are counted in window order,
// level by level: cell = ((level * R + z) * R + y) * R + x.

#include <vulkan/vulkan.h>

#include <cstdint>

#include "engine/graph/pass.hpp"

namespace voxgi::passes::lpv {

inline constexpr VkFormat kRsmFluxFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kRsmNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kRsmPositionFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

// Per cell and colour channel, four two-band SH coefficients (shaders/lpv/sh.glsl).
inline constexpr uint32_t kCoefficientsPerCell = 12;

// The LPV's buffers, one record per cell (shaders/lpv/cells.glsl):
//   Injected  lpv.inject's fixed-point sums: a 16-byte header (the largest contribution's
//             magnitude as float bits, the number of contributions that may add up in one
//             cell), then kCoefficientsPerCell int32 per cell
//   Radiance  lpv.propagate's result: per cell the SH per channel, the flux its geometry
//             stopped and the geometry, five vec4 (LPV_RADIANCE_VEC4S)
//   Work      lpv.propagate's scratch: two SH states (three vec4 per cell each), then the
//             geometry (one vec4 per cell)
enum class LpvBuffer { Injected, Radiance, Work };
VkDeviceSize lpv_buffer_bytes(LpvBuffer buffer, uint64_t cells);

// R^3 x levels of a clipmap resource; 0 for anything else.
uint64_t lpv_cell_count(const graph::ResourceInfo& clipmap);

// The size rule of an LPV buffer with one cell per voxel of the clipmap bound to
// `clipmap_slot`, and the validate check that reports `slot` when its buffer is smaller.
graph::SizeRule lpv_buffer_size(LpvBuffer buffer, const char* clipmap_slot);
void check_lpv_buffer(graph::PassCheck& check, LpvBuffer buffer, const char* slot,
                      const char* clipmap_slot);

inline uint32_t groups(uint64_t n, uint32_t local) {
  return static_cast<uint32_t>((n + local - 1) / local);
}

}  // namespace voxgi::passes::lpv
