// The constant ambient term: the placeholder for global illumination that GI families
// replace. Every surface receives a uniform environment radiance L from all directions, so its
// diffuse reflection is c_diff * L (times the material's occlusion).

#include <memory>
#include <optional>

#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "passes/common/passes.hpp"
#include "passes/common/shader_helpers.hpp"
#include "passes/contracts/gbuffer.hpp"

namespace voxgi::passes::common {
namespace {

using graph::Access;
using graph::ResourceKind;

struct AmbientPush {
  uint32_t width;
  uint32_t height;
  float radiance;  // 0 when the pass is switched off
  float pad;
};

class AmbientPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    pipeline_.emplace(graph::make_pass_compute(ctx, "common/ambient.comp",
                                               {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0}},
                                               sizeof(AmbientPush), false));
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const VkSampler nearest = ctx.gpu().sampler(gpu::SamplerKind::NearestClamp);
    const graph::BoundResource& base = ctx.resource("base_color");
    const graph::BoundResource& material = ctx.resource("material");
    const graph::BoundResource& depth = ctx.resource("depth");
    const graph::BoundResource& out = ctx.resource("radiance");
    const VkExtent3D extent = out.info->extent;
    const float radiance = ctx.flag("enabled") ? static_cast<float>(ctx.number("radiance")) : 0.0f;

    pipeline_->bind(cmd);
    gpu::DescriptorWriter()
        .sampled_image(0, base.view, base.layout, nearest)
        .sampled_image(1, material.view, material.layout, nearest)
        .sampled_image(2, depth.view, depth.layout, nearest)
        .storage_image(3, out.view, out.layout)
        .push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    pipeline_->push_constants(cmd, AmbientPush{extent.width, extent.height, radiance, 0.0f});
    dispatch_over_image(cmd, extent.width, extent.height);
  }

 private:
  std::optional<gpu::ComputePipeline> pipeline_;
};

}  // namespace

void register_ambient(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "common.ambient";
  info.doc = "Constant ambient light (uniform environment radiance), the placeholder for GI";
  info.inputs = {contracts::gbuffer_input(contracts::GbufferTarget::BaseColor),
                 contracts::gbuffer_input(contracts::GbufferTarget::Material),
                 contracts::gbuffer_input(contracts::GbufferTarget::Depth)};
  info.outputs = {radiance_output("radiance", "ambient radiance reflected towards the camera")};
  info.params = {
      {"enabled", graph::ParamType::Bool, 1.0, 0.0, 1.0, {}, "switch the ambient term off", true},
      {"radiance",
       graph::ParamType::Float,
       0.05,
       0.0,
       1e6,
       {},
       "uniform environment radiance L (W/sr/m^2); irradiance is pi*L",
       true},
  };
  registry.add(std::move(info), [] { return std::make_unique<AmbientPass>(); });
}

}  // namespace voxgi::passes::common
