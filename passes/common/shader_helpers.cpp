#include "passes/common/shader_helpers.hpp"

#include "engine/scene/gpu_scene.hpp"

namespace voxgi::passes::common {

std::vector<uint32_t> compile_common_shader(const graph::PassContext& ctx, const std::string& file,
                                            std::vector<gpu::ShaderDefine> defines) {
  gpu::ShaderRequest request;
  request.path = "common/" + file;
  request.defines = std::move(defines);
  return ctx.shaders().compile(request);
}

gpu::ComputePipeline make_common_compute(const graph::PassContext& ctx, const std::string& file,
                                         std::vector<gpu::Binding> bindings,
                                         uint32_t push_constant_size, bool with_scene_set,
                                         std::vector<gpu::ShaderDefine> defines) {
  gpu::PipelineLayoutDesc layout;
  layout.bindings = std::move(bindings);
  for (gpu::Binding& binding : layout.bindings) binding.stages = VK_SHADER_STAGE_COMPUTE_BIT;
  if (with_scene_set) layout.extra_set_layouts = {ctx.gpu_scene().set_layout()};
  layout.push_constant_size = push_constant_size;
  layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  return gpu::ComputePipeline(ctx.gpu(), compile_common_shader(ctx, file, std::move(defines)),
                              layout, ctx.pass_name());
}

void bind_scene_set(const graph::PassContext& ctx, const gpu::ComputePipeline& pipeline) {
  VkDescriptorSet set = ctx.gpu_scene().descriptor_set();
  vkCmdBindDescriptorSets(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 1, 1, &set,
                          0, nullptr);
}

graph::SlotSpec sampled_input(const char* name, const char* doc, bool optional,
                              std::vector<VkFormat> formats) {
  return {name,
          graph::kinds(graph::ResourceKind::Image2D),
          graph::Access::Sampled,
          graph::kStageCompute,
          std::move(formats),
          optional,
          doc};
}

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
  vkCmdDispatch(cmd, (width + kTile - 1) / kTile, (height + kTile - 1) / kTile, 1);
}

}  // namespace voxgi::passes::common
