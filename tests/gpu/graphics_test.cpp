#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/gpu/shader_files.hpp"

namespace voxgi::test {
namespace {

using GraphicsTest = GpuTest;

const char* kFullscreenVertex = R"(#version 460
void main() {
  vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  gl_Position = vec4(uv * 2.0 - 1.0, 0.0, 1.0);
}
)";

const char* kColorFragment = R"(#version 460
layout(push_constant) uniform Push { vec4 color; };
layout(location = 0) out vec4 out_color;
void main() { out_color = color; }
)";

TEST_F(GraphicsTest, ClearsAndDrawsFullscreenTriangle) {
  auto dir = make_temp_dir("voxgi-graphics");
  write_file(dir / "fullscreen.vert", kFullscreenVertex);
  write_file(dir / "color.frag", kColorFragment);
  gpu::ShaderCompiler compiler({dir}, "");

  gpu::GraphicsPipelineDesc desc;
  desc.vertex = compiler.compile({"fullscreen.vert"});
  desc.fragment = compiler.compile({"color.frag"});
  desc.layout.push_constant_size = 16;
  desc.layout.push_constant_stages = VK_SHADER_STAGE_FRAGMENT_BIT;
  desc.color_formats = {VK_FORMAT_R8G8B8A8_UNORM};
  desc.name = "test.fullscreen";
  gpu::GraphicsPipeline pipeline(context(), desc);

  const uint32_t size = 64;
  gpu::Image target(context(), {VK_IMAGE_TYPE_2D,
                                VK_FORMAT_R8G8B8A8_UNORM,
                                {size, size, 1},
                                1,
                                1,
                                VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                "test.target"});
  const float color[4] = {1.0f, 0.5f, 0.0f, 1.0f};
  context().immediate_submit([&](VkCommandBuffer cmd) {
    target.transition(cmd, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    attachment.imageView = target.view();
    attachment.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.clearValue.color = {{0.0f, 0.0f, 1.0f, 1.0f}};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {size, size}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = 1;
    rendering.pColorAttachments = &attachment;
    vkCmdBeginRendering(cmd, &rendering);
    pipeline.bind(cmd);
    // Only the left half is drawn, so the right half shows the clear colour.
    gpu::GraphicsPipeline::set_viewport(cmd, size / 2, size);
    pipeline.push_constants(cmd, color, sizeof(color));
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
  });
  auto pixels = target.download(VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  ASSERT_EQ(pixels.size(), size * size * 4);
  for (uint32_t y = 0; y < size; y += 7) {
    for (uint32_t x = 0; x < size; x += 5) {
      const uint8_t* p = &pixels[(y * size + x) * 4];
      if (x < size / 2) {
        EXPECT_EQ(p[0], 255) << x << "," << y;
        EXPECT_NEAR(p[1], 128, 1) << x << "," << y;
        EXPECT_EQ(p[2], 0) << x << "," << y;
      } else {
        EXPECT_EQ(p[0], 0) << x << "," << y;
        EXPECT_EQ(p[1], 0) << x << "," << y;
        EXPECT_EQ(p[2], 255) << x << "," << y;
      }
      EXPECT_EQ(p[3], 255);
    }
  }
}

TEST_F(GraphicsTest, DepthOnlyPipelineWithBiasAndGeometryShader) {
  if (!context().features().geometry_shader) GTEST_SKIP() << "device has no geometry shaders";
  auto dir = make_temp_dir("voxgi-graphics");
  write_file(dir / "fullscreen.vert", kFullscreenVertex);
  write_file(dir / "pass.geom", R"(#version 460
layout(triangles) in;
layout(triangle_strip, max_vertices = 3) out;
void main() {
  for (int i = 0; i < 3; ++i) {
    gl_Position = gl_in[i].gl_Position + vec4(0.0, 0.0, 0.5, 0.0);
    EmitVertex();
  }
  EndPrimitive();
}
)");
  gpu::ShaderCompiler compiler({dir}, "");
  gpu::GraphicsPipelineDesc desc;
  desc.vertex = compiler.compile({"fullscreen.vert"});
  desc.geometry = compiler.compile({"pass.geom"});
  desc.depth_test = true;
  desc.depth_write = true;
  desc.depth_bias = true;
  desc.depth_format = VK_FORMAT_D32_SFLOAT;
  desc.name = "test.depth";
  gpu::GraphicsPipeline pipeline(context(), desc);

  const uint32_t size = 16;
  gpu::Image depth(context(), {VK_IMAGE_TYPE_2D,
                               VK_FORMAT_D32_SFLOAT,
                               {size, size, 1},
                               1,
                               1,
                               VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                               "test.depth"});
  context().immediate_submit([&](VkCommandBuffer cmd) {
    depth.transition(cmd, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
    VkRenderingAttachmentInfo attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    attachment.imageView = depth.view();
    attachment.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.clearValue.depthStencil = {1.0f, 0};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {size, size}};
    rendering.layerCount = 1;
    rendering.pDepthAttachment = &attachment;
    vkCmdBeginRendering(cmd, &rendering);
    pipeline.bind(cmd);
    gpu::GraphicsPipeline::set_viewport(cmd, size, size);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
  });
  auto texels = depth.download(VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL);
  ASSERT_EQ(texels.size(), size * size * 4);
  float value = 0.0f;
  std::memcpy(&value, texels.data() + (5 * size + 5) * 4, 4);
  EXPECT_NEAR(value, 0.5f, 1e-4f);
}

TEST_F(GraphicsTest, ConservativeRasterizationIsRefusedWhenMissing) {
  if (context().features().conservative_rasterization) {
    GTEST_SKIP() << "device has conservative rasterization";
  }
  gpu::GraphicsPipelineDesc desc;
  desc.vertex = {0x07230203u, 0, 0, 0, 0};
  desc.conservative_rasterization = true;
  desc.name = "test.conservative";
  EXPECT_THROW(gpu::GraphicsPipeline(context(), desc), gpu::Error);
}

}  // namespace
}  // namespace voxgi::test
