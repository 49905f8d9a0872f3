#include "passes/contracts/shadow_data.hpp"

#include <algorithm>

#include "engine/gpu/context.hpp"

namespace voxgi::contracts {

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
