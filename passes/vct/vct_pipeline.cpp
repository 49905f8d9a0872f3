#include "passes/vct/vct_pipeline.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"

namespace voxgi::passes::vct {

VolumeSampler::VolumeSampler(gpu::Context& context) : context_(context) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  info.maxLod = VK_LOD_CLAMP_NONE;
  gpu::check(vkCreateSampler(context_.device(), &info, nullptr, &sampler_),
             "vkCreateSampler (vct volumes)");
}

VolumeSampler::~VolumeSampler() {
  vkDestroySampler(context_.device(), sampler_, nullptr);
}

graph::SlotSpec clipmap_info_input() {
  return {"clipmap_info",
          graph::kinds(graph::ResourceKind::Buffer),
          graph::Access::StorageRead,
          graph::kStageCompute,
          {},
          false,
          "VoxelClipmapInfo (contracts/voxel_clipmap.glsl) written by the voxelization pass"};
}

graph::SlotSpec sampled_clipmap(const char* name, const char* doc, bool optional,
                                std::vector<VkFormat> formats) {
  return {name,
          graph::kinds(graph::ResourceKind::Clipmap),
          graph::Access::Sampled,
          graph::kStageCompute,
          std::move(formats),
          optional,
          doc};
}

std::string unbound_directional_slots(const graph::PassDeclaration& pass) {
  std::string missing;
  for (const char* slot : kDirectionalSlots) {
    if (!pass.has(slot)) missing += std::string(missing.empty() ? "" : ", ") + slot;
  }
  return missing;
}

FilteredVolumes bound_filtered_volumes(const graph::PassDeclaration& pass) {
  return unbound_directional_slots(pass).empty() ? FilteredVolumes::Anisotropic
                                                 : FilteredVolumes::Isotropic;
}

void check_filtered_volumes_bound(graph::PassCheck& check) {
  const std::string missing = unbound_directional_slots(check);
  if (missing.empty() || check.has(kFilteredSlot)) return;
  check.slot_error(kFilteredSlot,
                   "bind either slot 'filtered' (isotropic) or all six directional slots "
                   "pos_x..neg_z (anisotropic); unbound: filtered, " +
                       missing);
}

}  // namespace voxgi::passes::vct
