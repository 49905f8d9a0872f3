#include "passes/contracts/gbuffer.hpp"

#include <utility>

namespace voxgi::contracts {
namespace {

template <size_t N>
std::vector<VkFormat> to_vector(const std::array<VkFormat, N>& list) {
  return {list.begin(), list.end()};
}

graph::SlotSpec sampled(const char* name, GbufferTarget target, const char* doc) {
  return {name,
          graph::kinds(graph::ResourceKind::Image2D),
          graph::Access::Sampled,
          graph::kStageCompute,
          gbuffer_formats(target),
          false,
          doc};
}

}  // namespace

std::vector<VkFormat> gbuffer_formats(GbufferTarget target) {
  switch (target) {
    case GbufferTarget::BaseColor:
      return to_vector(kGbufferBaseColorFormats);
    case GbufferTarget::Normal:
      return to_vector(kGbufferNormalFormats);
    case GbufferTarget::Material:
      return to_vector(kGbufferMaterialFormats);
    case GbufferTarget::Emission:
      return to_vector(kGbufferEmissionFormats);
    case GbufferTarget::Depth:
      break;
  }
  return {kGbufferDepthFormat};
}

graph::SlotSpec gbuffer_input(GbufferTarget target) {
  switch (target) {
    case GbufferTarget::BaseColor:
      return sampled("base_color", target, "G-buffer base colour");
    case GbufferTarget::Normal:
      return sampled("normal", target, "G-buffer normal + roughness");
    case GbufferTarget::Material:
      return sampled("material", target, "G-buffer metallic, roughness, occlusion, coverage");
    case GbufferTarget::Emission:
      return sampled("emission", target, "G-buffer emission");
    case GbufferTarget::Depth:
      break;
  }
  return sampled("depth", target, "G-buffer depth");
}

}  // namespace voxgi::contracts
