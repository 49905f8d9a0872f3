#include "passes/dvs/dvs_pipeline.hpp"

#include "engine/gpu/image.hpp"

namespace voxgi::passes::dvs {

graph::SlotSpec clipmap_input(const char* name, const char* doc, bool optional,
                              std::vector<VkFormat> formats) {
  return {name,
          graph::ResourceKind::Clipmap | graph::ResourceKind::Image3D,
          graph::Access::Sampled,
          graph::kStageCompute,
          std::move(formats),
          optional,
          doc};
}

graph::SlotSpec radiance_volume_output(const char* name, const char* doc, bool optional) {
  return {name,
          graph::ResourceKind::Clipmap | graph::ResourceKind::Image3D,
          graph::Access::StorageWrite,
          graph::kStageCompute,
          {VK_FORMAT_R16G16B16A16_SFLOAT},
          optional,
          doc};
}

VkImageView storage_view(const graph::BoundResource& resource) {
  if (resource.info->mip >= 0 || resource.info->mip_levels == 1) return resource.view;
  return resource.image->view(0);
}

void dispatch_over_volume(VkCommandBuffer cmd, VkExtent3D extent) {
  vkCmdDispatch(cmd, gpu::ComputePipeline::groups(extent.width, kVolumeTile),
                gpu::ComputePipeline::groups(extent.height, kVolumeTile),
                gpu::ComputePipeline::groups(extent.depth, kVolumeTile));
}

}  // namespace voxgi::passes::dvs
