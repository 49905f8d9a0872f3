#include <gtest/gtest.h>

#include <iostream>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/gpu/sync.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/gpu/shader_files.hpp"

namespace voxgi::test {
namespace {

using ComputeTest = GpuTest;

const char* kDoubleShader = R"(#version 460
layout(local_size_x = 64) in;
layout(set = 0, binding = 0, std430) readonly buffer Input { float values_in[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Output { float values_out[]; };
layout(push_constant) uniform Push { uint count; float scale; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < count) values_out[i] = values_in[i] * scale;
}
)";

TEST_F(ComputeTest, DoublesABufferWithPushDescriptors) {
  auto dir = make_temp_dir("voxgi-compute");
  write_file(dir / "double.comp", kDoubleShader);
  gpu::ShaderCompiler compiler({dir}, "");
  auto spirv = compiler.compile({"double.comp"});

  gpu::PipelineLayoutDesc layout;
  layout.bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                     {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  layout.push_constant_size = 8;
  layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  gpu::ComputePipeline pipeline(context(), spirv, layout, "test.double");

  const uint32_t count = 1000;
  std::vector<float> input(count);
  for (uint32_t i = 0; i < count; ++i) input[i] = float(i) - 10.5f;
  gpu::Buffer in(context(), count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                 gpu::MemoryUsage::GpuOnly, "test.in");
  gpu::Buffer out(context(), count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                  gpu::MemoryUsage::GpuOnly, "test.out");
  in.upload_vector(input);

  struct Push {
    uint32_t count;
    float scale;
  } push{count, 2.0f};
  context().immediate_submit([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    gpu::DescriptorWriter().storage_buffer(0, in).storage_buffer(1, out).push(
        cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout());
    pipeline.push_constants(cmd, push);
    vkCmdDispatch(cmd, gpu::ComputePipeline::groups(count, 64), 1, 1);
  });
  auto result = out.download_vector<float>();
  ASSERT_EQ(result.size(), count);
  for (uint32_t i = 0; i < count; ++i) ASSERT_EQ(result[i], input[i] * 2.0f) << "index " << i;
  EXPECT_EQ(gpu::ComputePipeline::groups(1000, 64), 16u);
  EXPECT_EQ(gpu::ComputePipeline::groups(64, 64), 1u);

  // Too many push-constant bytes are refused before reaching Vulkan.
  std::vector<uint8_t> too_big(16);
  context().immediate_submit([&](VkCommandBuffer cmd) {
    EXPECT_THROW(pipeline.push_constants(cmd, too_big.data(), 16), gpu::Error);
  });
}

// Guards the guard: two copies into the same buffer without a barrier must make
// synchronization validation speak up, so a clean run means something. (Copies, because the
// validation layer of this era does not track shader accesses through push descriptors.)
TEST_F(ComputeTest, SynchronizationValidationCatchesAMissingBarrier) {
  gpu::Buffer in(context(), 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly,
                 "test.hazard_in");
  gpu::Buffer out(context(), 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUsage::GpuOnly,
                  "test.hazard_out");
  std::cerr << "(the next validation message is expected)" << std::endl;
  context().immediate_submit([&](VkCommandBuffer cmd) {
    VkBufferCopy copy{0, 0, 64};
    vkCmdCopyBuffer(cmd, in.handle(), out.handle(), 1, &copy);
    vkCmdCopyBuffer(cmd, in.handle(), out.handle(), 1, &copy);
  });
  auto messages = context().validation_messages();
  context().clear_validation_messages();
  ASSERT_FALSE(messages.empty()) << "synchronization validation is not active";
  EXPECT_NE(messages[0].find("WRITE_AFTER_WRITE"), std::string::npos) << messages[0];
  EXPECT_NE(messages[0].find("test.hazard_out"), std::string::npos) << "debug names missing";
}

TEST_F(ComputeTest, RejectsCodeThatIsNotSpirv) {
  gpu::PipelineLayoutDesc layout;
  EXPECT_THROW(gpu::ComputePipeline(context(), {1, 2, 3}, layout, "test.garbage"), gpu::Error);
  EXPECT_THROW(gpu::ComputePipeline(context(), {}, layout, "test.empty"), gpu::Error);
}

}  // namespace
}  // namespace voxgi::test
