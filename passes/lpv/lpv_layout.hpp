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
// lpv.propagate's radiance buffer (lpv/cells.glsl, LPV_RADIANCE_VEC4S): per cell the SH per
// channel, the flux its geometry stopped and the geometry, five vec4.
inline constexpr VkDeviceSize kRadianceBytesPerCell = 5 * 16;
// The injection buffer: a 16-byte header (the largest contribution's magnitude as float bits,
// the number of contributions that may add up in one cell), then kCoefficientsPerCell
// fixed-point int32 per cell.
inline constexpr VkDeviceSize kInjectedHeaderBytes = 16;

// R^3 x levels of a clipmap resource; 0 for anything else.
uint64_t lpv_cell_count(const graph::ResourceInfo& clipmap);

// Size rules of the LPV buffers from the clipmap bound to `clipmap_slot`: the injection buffer,
// a float SH buffer (12 floats per cell) and `copies` of it.
graph::SizeRule injected_buffer_size(const char* clipmap_slot);
graph::SizeRule sh_buffer_size(const char* clipmap_slot, uint32_t copies = 1);
graph::SizeRule radiance_buffer_size(const char* clipmap_slot);

// For validate hooks: reports `slot` when its buffer is smaller than `copies` SH buffers (or
// the injection buffer) of the clipmap bound to `clipmap_slot`.
void check_sh_buffer(graph::PassCheck& check, const char* slot, const char* clipmap_slot,
                     uint32_t copies);
void check_radiance_buffer(graph::PassCheck& check, const char* slot, const char* clipmap_slot);
void check_injected_buffer(graph::PassCheck& check, const char* slot, const char* clipmap_slot);

inline uint32_t groups(uint64_t n, uint32_t local) {
  return static_cast<uint32_t>((n + local - 1) / local);
}

}  // namespace voxgi::passes::lpv
