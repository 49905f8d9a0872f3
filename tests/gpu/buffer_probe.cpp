#include "tests/gpu/buffer_probe.hpp"

#include "engine/gpu/pipeline.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {

void run_buffer_probe(gpu::ShaderCompiler& compiler, const std::string& probe, gpu::Buffer& input,
                      gpu::Buffer& output, uint32_t count) {
  gpu::Context& context = gpu_context();
  gpu::PipelineLayoutDesc layout;
  layout.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                     {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  layout.push_constant_size = sizeof(uint32_t);
  layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  gpu::ComputePipeline pipeline(context, compiler.compile({probe}), layout, probe);
  context.immediate_submit([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    gpu::DescriptorWriter().storage_buffer(0, input).storage_buffer(1, output).push(
        cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout());
    pipeline.push_constants(cmd, count);
    vkCmdDispatch(cmd, 1, 1, 1);
  });
}

}  // namespace voxgi::test
