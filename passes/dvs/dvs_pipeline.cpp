#include "passes/dvs/dvs_pipeline.hpp"

#include "engine/gpu/image.hpp"
#include "engine/scene/gpu_scene.hpp"

namespace voxgi::passes::dvs {

gpu::ComputePipeline make_dvs_compute(const graph::PassContext& ctx, const std::string& file,
                                      std::vector<gpu::Binding> bindings,
                                      uint32_t push_constant_size, bool with_scene_set,
                                      std::vector<gpu::ShaderDefine> defines) {
  gpu::ShaderRequest request;
  request.path = "dvs/" + file;
  request.defines = std::move(defines);
  gpu::PipelineLayoutDesc layout;
  layout.bindings = std::move(bindings);
  for (gpu::Binding& binding : layout.bindings) binding.stages = VK_SHADER_STAGE_COMPUTE_BIT;
  if (with_scene_set) layout.extra_set_layouts = {ctx.gpu_scene().set_layout()};
  layout.push_constant_size = push_constant_size;
  layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  return gpu::ComputePipeline(ctx.gpu(), ctx.shaders().compile(request), layout, ctx.pass_name());
}

void bind_scene_set(const graph::PassContext& ctx, const gpu::ComputePipeline& pipeline) {
  VkDescriptorSet set = ctx.gpu_scene().descriptor_set();
  vkCmdBindDescriptorSets(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 1, 1, &set,
                          0, nullptr);
}

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

graph::SlotSpec buffer_input(const char* name, const char* doc, bool optional) {
  return {name,
          graph::kinds(graph::ResourceKind::Buffer),
          graph::Access::StorageRead,
          graph::kStageCompute,
          {},
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

std::vector<uint64_t> InputVersions::current(const graph::PassContext& ctx) const {
  std::vector<uint64_t> versions;
  versions.reserve(slots_.size());
  // An unbound optional slot counts as version 0 (resource_version() wants a bound slot).
  for (const std::string& slot : slots_) {
    versions.push_back(ctx.has(slot) ? ctx.resource_version(slot) : 0);
  }
  return versions;
}

bool InputVersions::changed(const graph::PassContext& ctx) const {
  return stored_.empty() || stored_ != current(ctx);
}

void InputVersions::store(const graph::PassContext& ctx) {
  stored_ = current(ctx);
}

}  // namespace voxgi::passes::dvs
