#include "passes/contracts/filtered_volumes.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"

#include <limits>
#include <string>

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
