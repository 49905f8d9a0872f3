#include "passes/vct/vct_pipeline.hpp"

#include <stdexcept>

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
          "VoxelClipmapInfo (lib/voxel_clipmap.glsl) written by the voxelization pass"};
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

FilteredVolumes bound_filtered_volumes(const graph::PassContext& ctx) {
  bool all_directional = true;
  std::string missing;
  for (const char* slot : kDirectionalSlots) {
    if (!ctx.has(slot)) {
      all_directional = false;
      missing += std::string(missing.empty() ? "" : ", ") + slot;
    }
  }
  if (all_directional) return FilteredVolumes::Anisotropic;
  if (ctx.has(kFilteredSlot)) return FilteredVolumes::Isotropic;
  throw std::invalid_argument("pass '" + ctx.pass_name() +
                              "': bind either slot 'filtered' (isotropic) or all six directional "
                              "slots pos_x..neg_z (anisotropic); unbound: filtered, " +
                              missing);
}

FilteredVolumes require_filtered_volumes(const graph::PassContext& ctx, bool want_anisotropic) {
  if (!want_anisotropic) {
    if (!ctx.has(kFilteredSlot)) {
      throw std::invalid_argument("pass '" + ctx.pass_name() +
                                  "' field 'mode': mode 'isotropic' needs the output slot "
                                  "'filtered' bound");
    }
    return FilteredVolumes::Isotropic;
  }
  std::string missing;
  for (const char* slot : kDirectionalSlots) {
    if (!ctx.has(slot)) missing += std::string(missing.empty() ? "" : ", ") + slot;
  }
  if (!missing.empty()) {
    throw std::invalid_argument("pass '" + ctx.pass_name() +
                                "' field 'mode': mode 'anisotropic' needs the output slots "
                                "pos_x, neg_x, pos_y, neg_y, pos_z, neg_z bound; unbound: " +
                                missing);
  }
  return FilteredVolumes::Anisotropic;
}

}  // namespace voxgi::passes::vct
