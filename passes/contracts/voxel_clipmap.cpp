#include "passes/contracts/voxel_clipmap.hpp"

#include <string>

namespace voxgi::contracts {

graph::SlotSpec clipmap_info_input() {
  return {"clipmap_info",
          graph::kinds(graph::ResourceKind::Buffer),
          graph::Access::StorageRead,
          graph::kStageCompute,
          {},
          false,
          "VoxelClipmapInfo from common.voxelize (contracts/voxel_clipmap.glsl)"};
}

void check_clipmap_info_size(graph::PassCheck& check) {
  if (!check.has("clipmap_info")) return;
  const graph::ResourceInfo& info = check.info("clipmap_info");
  if (info.buffer_size >= kVoxelClipmapInfoBytes) return;
  check.slot_error("clipmap_info",
                   "buffer '" + info.name + "' holds " + std::to_string(info.buffer_size) +
                       " bytes; VoxelClipmapInfo needs " + std::to_string(kVoxelClipmapInfoBytes));
}

gpu::ShaderDefine clipmap_levels_define(uint32_t clipmap_levels) {
  return {"VOXEL_CLIPMAP_LEVELS", std::to_string(clipmap_levels)};
}

}  // namespace voxgi::contracts
