// lpv.rsm: reflective shadow maps (Dachsbacher and Stamminger; seed 002 sec. 3.3). For every
// light, the surfaces it sees first, with their world position, their normal facing the light
// and the flux they reflect (shaders/lpv/rsm.frag derives it), six array layers per light as
// the shadow maps lay them out (a point light uses all six, others the first). Re-renders only
// when lights or geometry change.

#include <algorithm>
#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "engine/scene/scene.hpp"
#include "passes/lpv/lpv_layout.hpp"
#include "passes/lpv/passes.hpp"
#include "passes/lpv/rsm_views.hpp"

namespace voxgi::passes::lpv {
namespace {

using graph::Access;
using graph::ResourceKind;

struct RsmPush {
  glm::mat4 view_proj;
  glm::vec4 origin;  // w: light index
  glm::vec4 info;    // perspective, extent, resolution
};

constexpr std::array<const char*, 3> kColorSlots = {"flux", "normal", "position"};

class RsmPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    gpu::GraphicsPipelineDesc desc;
    desc.name = ctx.pass_name();
    desc.vertex = graph::compile_pass_shader(ctx, "lpv/rsm.vert");
    desc.fragment = graph::compile_pass_shader(ctx, "lpv/rsm.frag");
    desc.layout.extra_set_layouts = {ctx.gpu_scene().set_layout()};
    desc.layout.push_constant_size = sizeof(RsmPush);
    desc.layout.push_constant_stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    desc.vertex_bindings = {scene::GpuScene::vertex_binding()};
    desc.vertex_attributes = scene::GpuScene::vertex_attributes();
    desc.depth_test = true;
    desc.depth_write = true;
    desc.depth_compare = VK_COMPARE_OP_LESS;
    desc.depth_clamp = true;  // surfaces behind an orthographic view's near plane still count
    desc.cull = VK_CULL_MODE_NONE;
    for (const char* slot : kColorSlots) desc.color_formats.push_back(ctx.info(slot).format);
    desc.depth_format = ctx.info("depth").format;
    pipeline_.emplace(ctx.gpu(), desc);
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    const graph::FrameInfo& frame = ctx.frame();
    if (frame.first_frame || frame.lights_changed || frame.geometry_changed ||
        ctx.params_changed()) {
      return {};
    }
    return "lights and geometry unchanged";
  }

  void execute(graph::PassContext& ctx) override {
    const scene::Scene& scene = ctx.scene();
    if (!sphere_ || ctx.frame().first_frame || ctx.frame().geometry_changed) {
      sphere_ = scene.bounding_sphere();
    }
    const graph::ResourceInfo& flux = ctx.info("flux");
    const uint32_t resolution = flux.extent.width;
    const uint32_t layers = flux.array_layers;
    const uint32_t slots = std::min<uint32_t>({layers / kRsmFacesPerLight,
                                               static_cast<uint32_t>(ctx.integer("max_lights")),
                                               static_cast<uint32_t>(scene.lights.size())});
    // Every layer is cleared; those of a light present also get its views.
    for (uint32_t light = 0; light * kRsmFacesPerLight < layers; ++light) {
      const std::vector<RsmView> views =
          light < slots ? rsm_views(scene.lights[light], *sphere_) : std::vector<RsmView>{};
      for (uint32_t face = 0; face < kRsmFacesPerLight; ++face) {
        if (light * kRsmFacesPerLight + face >= layers) break;
        std::optional<RsmPush> push;
        if (face < views.size()) {
          const RsmView& v = views[face];
          push = RsmPush{v.view_proj, glm::vec4(v.origin, static_cast<float>(light)),
                         glm::vec4(v.perspective ? 1.0f : 0.0f, v.extent,
                                   static_cast<float>(resolution), 0.0f)};
        }
        render_layer(ctx, light * kRsmFacesPerLight + face, resolution, push);
      }
    }
  }

 private:
  // Clears the layer, then draws the scene from the view when there is one.
  void render_layer(graph::PassContext& ctx, uint32_t layer, uint32_t resolution,
                    const std::optional<RsmPush>& push) {
    VkCommandBuffer cmd = ctx.cmd();
    std::array<VkRenderingAttachmentInfo, kColorSlots.size()> colors{};
    for (size_t i = 0; i < kColorSlots.size(); ++i) {
      const graph::BoundResource& target = ctx.resource(kColorSlots[i]);
      colors[i].sType = VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO;
      colors[i].imageView = target.image->layer_view(layer);
      colors[i].imageLayout = target.layout;
      colors[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      colors[i].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
      colors[i].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    }
    const graph::BoundResource& depth = ctx.resource("depth");
    VkRenderingAttachmentInfo depth_attachment{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    depth_attachment.imageView = depth.image->layer_view(layer);
    depth_attachment.imageLayout = depth.layout;
    depth_attachment.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth_attachment.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth_attachment.clearValue.depthStencil = {1.0f, 0};

    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = {{0, 0}, {resolution, resolution}};
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = static_cast<uint32_t>(colors.size());
    rendering.pColorAttachments = colors.data();
    rendering.pDepthAttachment = &depth_attachment;
    vkCmdBeginRendering(cmd, &rendering);
    const scene::GpuScene& scene = ctx.gpu_scene();
    if (push && !scene.draws().empty()) {
      pipeline_->bind(cmd);
      gpu::GraphicsPipeline::set_viewport(cmd, resolution, resolution);
      VkDescriptorSet scene_set = scene.descriptor_set();
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_->layout(), 1, 1,
                              &scene_set, 0, nullptr);
      pipeline_->push_constants(cmd, *push);
      scene.record_draws(cmd);
    }
    vkCmdEndRendering(cmd);
  }

  std::optional<gpu::GraphicsPipeline> pipeline_;
  std::optional<scene::BoundingSphere> sphere_;
};

graph::SlotSpec rsm_target(const char* name, VkFormat format, const char* doc) {
  return {name,
          graph::kinds(ResourceKind::Image2D),
          Access::ColorAttachment,
          graph::kStageFragment,
          {format},
          false,
          doc};
}

}  // namespace

void register_rsm(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "lpv.rsm";
  info.doc =
      "Reflective shadow maps (seed 002's RSMCreate): per light (directional: fitted "
      "orthographic, spot: perspective, point: six 90-degree faces) the first surfaces' "
      "position, normal and reflected flux";
  info.outputs = {
      rsm_target("flux", kRsmFluxFormat,
                 "rgb reflected flux per texel (W), a 1 where a surface is"),
      rsm_target("normal", kRsmNormalFormat, "xyz unit normal facing the light, w 1"),
      rsm_target("position", kRsmPositionFormat, "xyz world position, w 1 where a surface is"),
      {"depth",
       graph::kinds(ResourceKind::Image2D),
       Access::DepthAttachment,
       graph::kStageFragment,
       {VK_FORMAT_D32_SFLOAT},
       false,
       "depth test of the maps",
       true},
  };
  info.params = {
      {"max_lights",
       graph::ParamType::Int,
       64.0,
       0.0,
       64.0,
       {},
       "lights (in scene order) that get reflective shadow maps; the maps' layers / 6 limit it "
       "too",
       false,
       true},
      {"resolution",
       graph::ParamType::Int,
       256.0,
       4.0,
       4096.0,
       {},
       "edge of each map face in texels: the injected resolution (seed 002 injects 256^2 from "
       "1024^2 maps)",
       false,
       true},
  };
  const auto layers_rule = [](const graph::SizeQuery& query) {
    graph::DerivedSize size;
    size.width = size.height = static_cast<uint32_t>(query.number("resolution"));
    const double present =
        std::min(query.scene_value("scene.light_count"), query.number("max_lights"));
    size.layers = kRsmFacesPerLight * static_cast<uint32_t>(std::max(1.0, present));
    return size;
  };
  for (const char* slot : {"flux", "normal", "position", "depth"}) {
    graph::set_size_rule(info, slot, layers_rule);
  }
  info.may_skip = true;
  info.validate = [](graph::PassCheck& check) {
    if (!check.has("flux")) return;
    const graph::ResourceInfo& flux = check.info("flux");
    for (const char* slot : {"normal", "position", "depth"}) {
      if (!check.has(slot)) continue;
      const graph::ResourceInfo& other = check.info(slot);
      if (other.extent.width == flux.extent.width && other.extent.height == flux.extent.height &&
          other.array_layers == flux.array_layers) {
        continue;
      }
      check.slot_error(slot, "image '" + other.name + "' must have the extent and layers of '" +
                                 flux.name + "': the maps are rendered together, texel for texel");
    }
  };
  registry.add(std::move(info), [] { return std::make_unique<RsmPass>(); });
}

}  // namespace voxgi::passes::lpv
