// Deferred direct lighting in compute: for each pixel of the G-buffer, the glTF BRDF under
// every punctual light of the scene (KHR_lights_punctual units and falloffs), shadowed by the
// shadow maps when they are bound, plus the surface's emission.

#include <algorithm>
#include <memory>
#include <optional>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "engine/scene/gpu_scene.hpp"
#include "passes/common/passes.hpp"
#include "passes/common/shader_helpers.hpp"
#include "passes/contracts/gbuffer.hpp"
#include "passes/contracts/shadow_data.hpp"

namespace voxgi::passes::common {
namespace {

struct LightingPush {
  uint32_t width;
  uint32_t height;
  uint32_t shadow_slots;  // lights with an entry in the shadow data
  uint32_t shadows_enabled;
  float normal_bias;  // in shadow-map texels
  int32_t pcf_radius;
  float background;  // radiance where no geometry was drawn
  float pad;
};

class DeferredLightingPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    has_shadows_ = ctx.has("shadow_maps") && ctx.has("shadow_matrices");
    std::vector<gpu::Binding> bindings = {
        {0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0},
    };
    if (has_shadows_) {
      bindings.push_back({6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      bindings.push_back({7, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0});
    }
    pipeline_.emplace(graph::make_pass_compute(ctx, "common/deferred_lighting.comp", bindings,
                                               sizeof(LightingPush), true,
                                               {{"HAS_SHADOWS", has_shadows_ ? "1" : "0"}}));
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const graph::BoundResource& out = ctx.resource("radiance");
    const VkExtent3D extent = out.info->extent;
    gpu::Context& gpu = ctx.gpu();
    const VkSampler nearest = gpu.sampler(gpu::SamplerKind::NearestClamp);

    gpu::DescriptorWriter writer;
    writer.uniform_buffer(0, *ctx.frame().uniform_buffer);
    const char* gbuffer_slots[] = {"base_color", "normal", "material", "emission", "depth"};
    for (uint32_t i = 0; i < 5; ++i) {
      const graph::BoundResource& r = ctx.resource(gbuffer_slots[i]);
      writer.sampled_image(1 + i, r.view, r.layout, nearest);
    }
    writer.storage_image(8, out.view, out.layout);
    LightingPush push{extent.width,
                      extent.height,
                      0,
                      0,
                      static_cast<float>(ctx.number("normal_bias")),
                      ctx.integer("pcf_radius"),
                      static_cast<float>(ctx.number("background")),
                      0.0f};
    if (has_shadows_) {
      push.shadow_slots = contracts::write_shadow_inputs(ctx, writer, 6, 7);
      push.shadows_enabled = ctx.flag("shadows") ? 1u : 0u;
    }
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    graph::bind_scene_set(ctx, *pipeline_);
    pipeline_->push_constants(cmd, push);
    dispatch_over_image(cmd, extent.width, extent.height);
  }

 private:
  bool has_shadows_ = false;
  std::optional<gpu::ComputePipeline> pipeline_;
};

}  // namespace

void register_deferred_lighting(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "common.deferred_lighting";
  info.doc =
      "Direct lighting of the G-buffer by all punctual lights with the glTF BRDF, shadow maps "
      "(PCF) and emission";
  info.inputs = {
      contracts::gbuffer_input(contracts::GbufferTarget::BaseColor),
      contracts::gbuffer_input(contracts::GbufferTarget::Normal),
      contracts::gbuffer_input(contracts::GbufferTarget::Material),
      contracts::gbuffer_input(contracts::GbufferTarget::Emission),
      contracts::gbuffer_input(contracts::GbufferTarget::Depth),
      contracts::shadow_maps_input("from common.shadow_maps; unbound: no shadows"),
      contracts::shadow_matrices_input("from common.shadow_maps"),
  };
  info.outputs = {
      radiance_output("radiance", "direct radiance towards the camera, emission included")};
  info.params = {
      {"shadows", graph::ParamType::Bool, 1.0, 0.0, 1.0, {}, "test the shadow maps", true},
      {"pcf_radius",
       graph::ParamType::Int,
       1.0,
       0.0,
       3.0,
       {},
       "percentage-closer filter radius in texels ((2r+1)^2 taps)",
       true},
      {"normal_bias",
       graph::ParamType::Float,
       1.5,
       0.0,
       16.0,
       {},
       "offset of the shadow lookup along the normal, in shadow-map texels",
       true},
      {"background",
       graph::ParamType::Float,
       0.0,
       0.0,
       1e6,
       {},
       "radiance of pixels where no geometry was drawn",
       true},
  };
  registry.add(std::move(info), [] { return std::make_unique<DeferredLightingPass>(); });
}

}  // namespace voxgi::passes::common
