// Composite: direct radiance plus whatever indirect terms the graph provides. Indirect diffuse
// and specular radiance are optional inputs, ambient occlusion (r channel) scales them. The
// optional `indirect` output holds the indirect radiance exactly as added to the image, so that
// benchmarks can compare it with a reference's indirect component.

#include <memory>
#include <optional>

#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "passes/common/passes.hpp"
#include "passes/common/shader_helpers.hpp"

namespace voxgi::passes::common {
namespace {

using graph::Access;
using graph::ResourceKind;

struct CompositePush {
  uint32_t width;
  uint32_t height;
  float indirect_scale;
  float pad;
};

constexpr const char* kOptionalInputs[] = {"indirect_diffuse", "indirect_specular",
                                           "ambient_occlusion"};
constexpr const char* kOptionalDefines[] = {"HAS_DIFFUSE", "HAS_SPECULAR", "HAS_AO"};

class CompositePass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    std::vector<gpu::Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                          {4, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0}};
    std::vector<gpu::ShaderDefine> defines;
    for (uint32_t i = 0; i < 3; ++i) {
      const bool bound = ctx.has(kOptionalInputs[i]);
      if (bound) bindings.push_back({1 + i, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      defines.push_back({kOptionalDefines[i], bound ? "1" : "0"});
    }
    const bool indirect_out = ctx.has("indirect");
    if (indirect_out) bindings.push_back({5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
    defines.push_back({"HAS_INDIRECT_OUT", indirect_out ? "1" : "0"});
    pipeline_.emplace(graph::make_pass_compute(ctx, "common/composite.comp", bindings,
                                               sizeof(CompositePush), false, defines));
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const VkSampler nearest = ctx.gpu().sampler(gpu::SamplerKind::NearestClamp);
    const graph::BoundResource& direct = ctx.resource("direct");
    const graph::BoundResource& out = ctx.resource("radiance");
    gpu::DescriptorWriter writer;
    writer.sampled_image(0, direct.view, direct.layout, nearest);
    for (uint32_t i = 0; i < 3; ++i) {
      if (!ctx.has(kOptionalInputs[i])) continue;
      const graph::BoundResource& r = ctx.resource(kOptionalInputs[i]);
      writer.sampled_image(1 + i, r.view, r.layout, nearest);
    }
    writer.storage_image(4, out.view, out.layout);
    if (ctx.has("indirect")) {
      const graph::BoundResource& indirect = ctx.resource("indirect");
      writer.storage_image(5, indirect.view, indirect.layout);
    }
    const VkExtent3D extent = out.info->extent;
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    pipeline_->push_constants(
        cmd, CompositePush{extent.width, extent.height,
                           static_cast<float>(ctx.number("indirect_scale")), 0.0f});
    dispatch_over_image(cmd, extent.width, extent.height);
  }

 private:
  std::optional<gpu::ComputePipeline> pipeline_;
};

}  // namespace

void register_composite(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "common.composite";
  info.doc = "Sums direct and indirect radiance; ambient occlusion scales the indirect terms";
  info.inputs = {graph::sampled_2d_input("direct", "direct radiance (emission included)", false),
                 graph::sampled_2d_input("indirect_diffuse", "indirect diffuse radiance", true),
                 graph::sampled_2d_input("indirect_specular", "indirect specular radiance", true),
                 graph::sampled_2d_input("ambient_occlusion",
                                         "ambient occlusion in r (1 = unoccluded)", true)};
  graph::SlotSpec indirect_output = radiance_output(
      "indirect", "the indirect radiance as added to the image (AO and scale applied)");
  indirect_output.optional = true;
  info.outputs = {radiance_output("radiance", "scene-referred linear radiance"),
                  std::move(indirect_output)};
  info.params = {{"indirect_scale",
                  graph::ParamType::Float,
                  1.0,
                  0.0,
                  16.0,
                  {},
                  "multiplier of the indirect terms (1 = physically based)",
                  true}};
  registry.add(std::move(info), [] { return std::make_unique<CompositePass>(); });
}

}  // namespace voxgi::passes::common
