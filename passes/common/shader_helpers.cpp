#include "passes/common/shader_helpers.hpp"

namespace voxgi::passes::common {

graph::SlotSpec radiance_output(const char* name, const char* doc) {
  return {name,
          graph::kinds(graph::ResourceKind::Image2D),
          graph::Access::StorageWrite,
          graph::kStageCompute,
          {VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R32G32B32A32_SFLOAT},
          false,
          doc};
}

void dispatch_over_image(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
  vkCmdDispatch(cmd, graph::workgroups(width, kTile), graph::workgroups(height, kTile), 1);
}

}  // namespace voxgi::passes::common
