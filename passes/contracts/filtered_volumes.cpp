#include "passes/contracts/filtered_volumes.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"

#include <limits>
#include <string>
#include <string_view>
#include <utility>

namespace voxgi::contracts {

gpu::ShaderDefine unwrapped_windows_define(uint32_t clipmap_levels) {
  return {"VCT_UNWRAPPED_WINDOWS", clipmap_levels == 1 ? "1" : "0"};
}

gpu::ShaderDefine refine_levels_define(int levels) {
  return {"VCT_REFINE_LEVELS", std::to_string(levels)};
}

graph::ParamSpec refine_levels_param(int default_levels) {
  return {"refine",
          graph::ParamType::Int,
          static_cast<double>(default_levels),
          0.0,
          3.0,
          {},
          "where a cone's step holds a surface, march it again at voxels 2^refine finer, so "
          "that surfaces stop cones where they are, not a voxel early (docs/vct.md); 0 is off; "
          "at 64^3 and above 1 lowers the Cornell box's one-bounce relMSE by 16-26%, 2 by a "
          "further 10-17% with 9 and 16 cones, at 1.1-1.2x the gather's cost on lavapipe",
          false};
}

graph::ParamSpec cone_max_distance_param() {
  return {"max_distance",
          graph::ParamType::Float,
          0.0,
          0.0,
          1e6,
          {},
          "longest cone, in scene units; 0: no limit (cones stop where they are opaque or leave "
          "the clipmap)",
          true};
}

float cone_max_distance(double value) {
  return value > 0.0 ? static_cast<float>(value) : std::numeric_limits<float>::max();
}

bool front_light_bound(const graph::PassDeclaration& pass) {
  return pass.has(kFacingSlots[0]) && pass.has(kFacingSlots[1]);
}

void validate_front_light_slots(graph::PassCheck& check) {
  const bool pos = check.has(kFacingSlots[0]), neg = check.has(kFacingSlots[1]);
  if (!pos && !neg) return;
  if (pos != neg) {
    check.slot_error(pos ? kFacingSlots[1] : kFacingSlots[0],
                     "the front-light mode needs both facing_pos and facing_neg bound");
    return;
  }
  for (const char* slot : kDirectionalSlots) {
    if (!check.has(slot)) {
      check.slot_error(kFacingSlots[0],
                       "the facing volumes go with the six directional volumes pos_x..neg_z; "
                       "unbound: " +
                           std::string(slot));
      return;
    }
  }
}

gpu::ShaderDefine front_light_define(bool front_light) {
  return {"VCT_FRONT_LIGHT", front_light ? "1" : "0"};
}

uint32_t volume_array_size(bool anisotropic, bool front_light) {
  if (!anisotropic) return 1;
  return front_light ? 8u : 6u;
}

graph::SlotSpec filtered_volume_input(const char* name, std::string doc) {
  return {name,
          graph::kinds(graph::ResourceKind::Clipmap),
          graph::Access::Sampled,
          graph::kStageCompute,
          {VK_FORMAT_R16G16B16A16_SFLOAT},
          true,
          std::move(doc)};
}

graph::SlotSpec facing_input(const char* slot) {
  return filtered_volume_input(
      slot, std::string("facing volume from vct.filter (front-light mode): per axis the share of "
                        "the opacity facing across it, for cones travelling ") +
                (std::string_view(slot) == kFacingSlots[0] ? "+X, +Y, +Z" : "-X, -Y, -Z"));
}

std::vector<VkDescriptorImageInfo> filtered_volume_images(graph::PassContext& ctx, bool anisotropic,
                                                          bool front_light, VkSampler sampler) {
  std::vector<VkDescriptorImageInfo> images;
  auto add = [&](const char* slot) {
    const graph::BoundResource& v = ctx.resource(slot);
    images.push_back({sampler, v.view, v.layout});
  };
  if (!anisotropic) {
    add(kFilteredSlot);
    return images;
  }
  for (const char* slot : kDirectionalSlots) add(slot);
  if (front_light) {
    for (const char* slot : kFacingSlots) add(slot);
  }
  return images;
}

VolumeSampler::VolumeSampler(gpu::Context& context) : context_(context) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  info.maxLod = VK_LOD_CLAMP_NONE;
  gpu::check(vkCreateSampler(context_.device(), &info, nullptr, &sampler_),
             "vkCreateSampler (filtered volumes)");
}

VolumeSampler::~VolumeSampler() {
  vkDestroySampler(context_.device(), sampler_, nullptr);
}

}  // namespace voxgi::contracts
