// G-buffer: rasterises every scene instance once and stores what deferred shading needs, in
// the encoding of the G-buffer contract (passes/contracts/gbuffer.hpp,
// shaders/contracts/gbuffer.glsl).

#include <array>
#include <memory>
#include <optional>

#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "passes/common/passes.hpp"
#include "passes/common/shader_helpers.hpp"
#include "passes/contracts/gbuffer.hpp"

namespace voxgi::passes::common {
namespace {

using graph::Access;
using graph::ResourceKind;

class GbufferPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    gpu::GraphicsPipelineDesc desc;
    desc.name = ctx.pass_name();
    desc.vertex = graph::compile_pass_shader(ctx, "common/gbuffer.vert");
    desc.fragment = graph::compile_pass_shader(ctx, "common/gbuffer.frag");
    desc.layout.bindings = {{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER,
                             VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT}};
    desc.layout.extra_set_layouts = {ctx.gpu_scene().set_layout()};
    desc.vertex_bindings = {scene::GpuScene::vertex_binding()};
    desc.vertex_attributes = scene::GpuScene::vertex_attributes();
    desc.depth_test = true;
    desc.depth_write = true;
    desc.depth_compare = VK_COMPARE_OP_LESS;
    desc.front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    for (const char* slot : contracts::kGbufferColorSlots)
      desc.color_formats.push_back(ctx.info(slot).format);
    desc.depth_format = ctx.info("depth").format;

    desc.cull = VK_CULL_MODE_BACK_BIT;
    single_sided_.emplace(ctx.gpu(), desc);
    desc.cull = VK_CULL_MODE_NONE;
    desc.name += ".double_sided";
    double_sided_.emplace(ctx.gpu(), desc);
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const graph::ResourceInfo& depth_info = ctx.info("depth");
    const uint32_t width = depth_info.extent.width;
    const uint32_t height = depth_info.extent.height;

    std::array<VkRenderingAttachmentInfo, contracts::kGbufferColorSlots.size()> colors{};
    for (size_t i = 0; i < contracts::kGbufferColorSlots.size(); ++i) {
      const graph::BoundResource& target = ctx.resource(contracts::kGbufferColorSlots[i]);
      colors[i].sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
      colors[i].imageView = target.view;
      colors[i].imageLayout = target.layout;
      colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      colors[i].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    }
    const graph::BoundResource& depth = ctx.resource("depth");
    VkRenderingAttachmentInfo depth_attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth_attachment.imageView = depth.view;
    depth_attachment.imageLayout = depth.layout;
    depth_attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth_attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    depth_attachment.clearValue.depthStencil = {1.0f, 0};

    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {width, height}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = static_cast<uint32_t>(colors.size());
    rendering.pColorAttachments = colors.data();
    rendering.pDepthAttachment = &depth_attachment;
    vkCmdBeginRendering(cmd, &rendering);

    const scene::GpuScene& scene = ctx.gpu_scene();
    if (!scene.draws().empty()) {
      gpu::GraphicsPipeline::set_viewport(cmd, width, height);
      const bool cull_back_faces = ctx.flag("cull_back_faces");
      for (const gpu::GraphicsPipeline* pipeline : {&*single_sided_, &*double_sided_}) {
        const bool double_sided_pipeline = pipeline == &*double_sided_;
        pipeline->bind(cmd);
        gpu::DescriptorWriter()
            .uniform_buffer(0, *ctx.frame().uniform_buffer)
            .push(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->layout());
        VkDescriptorSet scene_set = scene.descriptor_set();
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline->layout(), 1, 1,
                                &scene_set, 0, nullptr);
        scene.record_draws(cmd, [&](const scene::GpuScene::Draw& draw) {
          return (draw.double_sided || !cull_back_faces) == double_sided_pipeline;
        });
      }
    }
    vkCmdEndRendering(cmd);
  }

 private:
  std::optional<gpu::GraphicsPipeline> single_sided_;
  std::optional<gpu::GraphicsPipeline> double_sided_;
};

graph::SlotSpec color_target(const char* name, std::vector<VkFormat> formats, const char* doc) {
  return {name,
          graph::kinds(ResourceKind::Image2D),
          Access::ColorAttachment,
          graph::kStageFragment,
          std::move(formats),
          false,
          doc};
}

}  // namespace

void register_gbuffer(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "common.gbuffer";
  info.doc =
      "Rasterises the scene into a G-buffer (base colour, normal, material, emission, depth)";
  info.outputs = {
      color_target("base_color", contracts::gbuffer_formats(contracts::GbufferTarget::BaseColor),
                   "linear base colour, a = occlusion"),
      color_target("normal", contracts::gbuffer_formats(contracts::GbufferTarget::Normal),
                   "world-space shading normal, w = roughness"),
      color_target("material", contracts::gbuffer_formats(contracts::GbufferTarget::Material),
                   "metallic, roughness, occlusion, coverage"),
      color_target("emission", contracts::gbuffer_formats(contracts::GbufferTarget::Emission),
                   "emitted radiance"),
      {"depth",
       graph::kinds(ResourceKind::Image2D),
       Access::DepthAttachment,
       graph::kStageFragment,
       {contracts::kGbufferDepthFormat},
       false,
       "depth, cleared to 1"},
  };
  info.params = {{"cull_back_faces",
                  graph::ParamType::Bool,
                  1.0,
                  0.0,
                  1.0,
                  {},
                  "cull back faces of single-sided materials (glTF doubleSided=false)",
                  true}};
  registry.add(std::move(info), [] { return std::make_unique<GbufferPass>(); });
}

}  // namespace voxgi::passes::common
