#pragma once
// Contract: the voxel clipmap description common.voxelize writes (the graph's clipmap_info
// buffer) and every voxel consumer reads. GLSL twin: shaders/contracts/voxel_clipmap.glsl,
// which also documents the addressing (levels stacked in z, toroidal storage, anchor-relative
// positions).

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>

#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::contracts {

inline constexpr uint32_t kVoxelMaxLevels = 8;  // VOXEL_CLIPMAP_MAX_LEVELS

// std430 mirror of VoxelClipmapLevel.
struct VoxelClipmapLevelInfo {
  glm::ivec4 origin_voxel;    // xyz: window min corner in voxels counted from the anchor; w: valid
  glm::vec4 min_corner_size;  // xyz: window min corner relative to the anchor (m); w: voxel edge
};
// std430 mirror of the VoxelClipmapInfo buffer block.
struct VoxelClipmapInfo {
  glm::vec4 anchor;  // xyz: world-space anchor (m)
  glm::uvec4 dims;   // x: R (voxels per level edge), y: L (levels)
  VoxelClipmapLevelInfo levels[kVoxelMaxLevels];
};
// The smallest clipmap_info buffer a consumer accepts.
inline constexpr uint64_t kVoxelClipmapInfoBytes = sizeof(VoxelClipmapInfo);
static_assert(sizeof(VoxelClipmapLevelInfo) == 32);
static_assert(offsetof(VoxelClipmapInfo, dims) == 16);
static_assert(offsetof(VoxelClipmapInfo, levels) == 32);
static_assert(kVoxelClipmapInfoBytes == 16 + 16 + kVoxelMaxLevels * 32);

// A reader's "clipmap_info" slot: the buffer read as a storage buffer in compute.
graph::SlotSpec clipmap_info_input();
// For validate hooks of the writer and the readers: reports slot "clipmap_info" when its
// buffer is smaller than VoxelClipmapInfo.
void check_clipmap_info_size(graph::PassCheck& check);

// VOXEL_CLIPMAP_LEVELS for a shader that reads a clipmap of `clipmap_levels` levels: the bound
// of voxel_finest_level's unrolled search, which otherwise tries all kVoxelMaxLevels.
gpu::ShaderDefine clipmap_levels_define(uint32_t clipmap_levels);

}  // namespace voxgi::contracts
