#include <gtest/gtest.h>

#include "engine/color/display_transform.hpp"
#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/gpu/shader_files.hpp"

namespace voxgi::color {
namespace {

const char* kApplyLutShader = R"(#version 460
#extension GL_GOOGLE_include_directive : require
#include "lib/display_lut.glsl"
layout(local_size_x = 64) in;
layout(set = 0, binding = 0) uniform sampler3D lut;
layout(set = 0, binding = 1, std430) readonly buffer In { vec4 linear[]; };
layout(set = 0, binding = 2, std430) writeonly buffer Out { vec4 display[]; };
layout(push_constant) uniform Push { uint count; float shaper_min; float shaper_max; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < count) display[i] = vec4(apply_display_lut(lut, linear[i].rgb, vec2(shaper_min, shaper_max)), 1.0);
}
)";

class DisplayLutGpu : public test::GpuTest {};

// The GLSL in shaders/lib/display_lut.glsl computes what DisplayTransform::apply_lut does.
TEST_F(DisplayLutGpu, ShaderMatchesTheCpuLutMath) {
  const DisplayTransform transform;
  const DisplayTransform::Lut lut = transform.bake("sRGB", "ACES 1.0 SDR-video", 33);
  gpu::ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_3D;
  desc.format = VK_FORMAT_R32G32B32A32_SFLOAT;
  desc.extent = {lut.size, lut.size, lut.size};
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
  desc.name = "test.display_lut";
  gpu::Image image(context(), desc);
  image.upload(lut.rgba.data(), lut.rgba.size() * sizeof(float),
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);

  std::vector<glm::vec4> inputs;
  for (float r : {0.0f, 1e-5f, 0.003f, 0.18f, 0.9f, 1.0f, 7.0f, 300.0f}) {
    for (float g : {0.0f, 0.05f, 1.0f, 20.0f}) {
      inputs.emplace_back(r, g, r * 0.5f + 0.01f, 1.0f);
    }
  }
  inputs.emplace_back(-1.0f, 0.0f, 0.0f, 1.0f);
  const uint32_t count = static_cast<uint32_t>(inputs.size());
  gpu::Buffer in(context(), count * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                 gpu::MemoryUsage::GpuOnly, "test.lut_in");
  gpu::Buffer out(context(), count * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                  gpu::MemoryUsage::GpuOnly, "test.lut_out");
  in.upload_vector(inputs);

  const auto dir = test::make_temp_dir("voxgi-display-lut");
  test::write_file(dir / "apply_lut.comp", kApplyLutShader);
  gpu::ShaderCompiler compiler({dir, std::filesystem::path(VOXGI_SOURCE_DIR) / "shaders"}, "");
  gpu::PipelineLayoutDesc layout;
  layout.bindings = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, VK_SHADER_STAGE_COMPUTE_BIT},
                     {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT},
                     {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT}};
  layout.push_constant_size = 12;
  layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  gpu::ComputePipeline pipeline(context(), compiler.compile({"apply_lut.comp"}), layout,
                                "test.apply_lut");
  struct Push {
    uint32_t count;
    float shaper_min, shaper_max;
  } push{count, lut.shaper_min_log2, lut.shaper_max_log2};
  context().immediate_submit([&](VkCommandBuffer cmd) {
    pipeline.bind(cmd);
    gpu::DescriptorWriter()
        .sampled_image(0, image.view(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                       context().sampler(gpu::SamplerKind::LinearClamp))
        .storage_buffer(1, in)
        .storage_buffer(2, out)
        .push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout());
    pipeline.push_constants(cmd, push);
    vkCmdDispatch(cmd, gpu::ComputePipeline::groups(count, 64), 1, 1);
  });
  const auto result = out.download_vector<glm::vec4>();
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 expected = DisplayTransform::apply_lut(lut, glm::vec3(inputs[i]));
    for (int c = 0; c < 3; ++c) {
      // Texture units interpolate with reduced weight precision; stay within 1/4 of a code.
      EXPECT_NEAR(result[i][c], expected[c], 0.25f / 255.0f) << "sample " << i << " channel " << c;
    }
  }
}

}  // namespace
}  // namespace voxgi::color
