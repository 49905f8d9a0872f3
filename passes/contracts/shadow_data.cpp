#include "passes/contracts/shadow_data.hpp"

#include <algorithm>
#include <utility>

#include "engine/gpu/context.hpp"

namespace voxgi::contracts {

graph::SlotSpec shadow_maps_input(std::string doc) {
  return {"shadow_maps",          graph::kinds(graph::ResourceKind::Image2D),
          graph::Access::Sampled, graph::kStageCompute,
          {kShadowMapFormat},     true,
          std::move(doc)};
}

graph::SlotSpec shadow_matrices_input(std::string doc) {
  return {"shadow_matrices",
          graph::kinds(graph::ResourceKind::Buffer),
          graph::Access::StorageRead,
          graph::kStageCompute,
          {},
          true,
          std::move(doc)};
}

uint32_t write_shadow_inputs(const graph::PassContext& ctx, gpu::DescriptorWriter& writer,
                             uint32_t maps_binding, uint32_t lights_binding) {
  const graph::BoundResource& maps = ctx.resource("shadow_maps");
  const graph::BoundResource& matrices = ctx.resource("shadow_matrices");
  writer.sampled_image(maps_binding, maps.view, maps.layout,
                       ctx.gpu().sampler(gpu::SamplerKind::ShadowCompare));
  writer.storage_buffer(lights_binding, *matrices.buffer);
  return std::min<uint32_t>(maps.info->array_layers / kShadowFacesPerLight,
                            static_cast<uint32_t>(matrices.info->buffer_size / kShadowLightBytes));
}

}  // namespace voxgi::contracts
