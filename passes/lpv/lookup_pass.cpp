// lpv.lookup: per pixel, the irradiance the accumulated LPV gives the G-buffer's surface,
// as outgoing diffuse radiance c_diff / pi x E (shaders/lpv/lookup.comp derives it).

#include <memory>
#include <optional>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"
#include "passes/contracts/gbuffer.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "passes/lpv/lpv_layout.hpp"
#include "passes/lpv/passes.hpp"

namespace voxgi::passes::lpv {
namespace {

struct LookupPush {
  float normal_offset;
  uint32_t surface_flux;
  float pad[2];
};

constexpr uint32_t kTile = 8;

class LookupPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    pipeline_.emplace(graph::make_pass_compute(ctx, "lpv/lookup.comp",
                                               {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                                {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                                {2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 0},
                                                {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                                {7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0}},
                                               sizeof(LookupPush), false));
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const VkSampler nearest = ctx.gpu().sampler(gpu::SamplerKind::NearestClamp);
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("clipmap_info").buffer)
        .storage_buffer(1, *ctx.resource("radiance").buffer)
        .uniform_buffer(2, *ctx.frame().uniform_buffer);
    uint32_t binding = 3;
    for (const char* slot : {"base_color", "normal", "material", "depth"}) {
      const graph::BoundResource& r = ctx.resource(slot);
      writer.sampled_image(binding++, r.view, r.layout, nearest);
    }
    const graph::BoundResource& out = ctx.resource("diffuse");
    writer.storage_image(7, out.view, out.layout);
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    pipeline_->push_constants(cmd, LookupPush{static_cast<float>(ctx.number("normal_offset")),
                                              ctx.choice("irradiance") == "surface_flux" ? 1u : 0u,
                                              {}});
    const VkExtent3D e = out.info->extent;
    vkCmdDispatch(cmd, graph::workgroups(e.width, kTile), graph::workgroups(e.height, kTile), 1);
  }

 private:
  std::optional<gpu::ComputePipeline> pipeline_;
};

}  // namespace

void register_lookup(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "lpv.lookup";
  info.doc =
      "Indirect diffuse light per pixel from the accumulated LPV: trilinear SH at the surface "
      "moved along its normal, irradiance towards the normal, x c_diff / pi";
  using contracts::GbufferTarget;
  info.inputs = {
      contracts::clipmap_info_input(),
      graph::compute_buffer_slot(
          "radiance", graph::Access::StorageRead,
          "lpv.merge's volume: accumulated intensities, stopped flux, geometry"),
      contracts::gbuffer_input(GbufferTarget::BaseColor),
      contracts::gbuffer_input(GbufferTarget::Normal),
      contracts::gbuffer_input(GbufferTarget::Material),
      contracts::gbuffer_input(GbufferTarget::Depth),
  };
  info.outputs = {{"diffuse",
                   graph::kinds(graph::ResourceKind::Image2D),
                   graph::Access::StorageWrite,
                   graph::kStageCompute,
                   {VK_FORMAT_R16G16B16A16_SFLOAT},
                   false,
                   "indirect diffuse radiance"}};
  info.params = {{"normal_offset",
                  graph::ParamType::Float,
                  0.5,
                  0.0,
                  2.0,
                  {},
                  "distance the lookup moves off the surface along its normal, in cells "
                  "(against back-bleeding), for the SH lookup",
                  true},
                 {"irradiance",
                  graph::ParamType::Enum,
                  0.0,
                  0.0,
                  0.0,
                  {"surface_flux", "sh"},
                  "surface_flux: the flux the surface's cells stopped over their cross-section "
                  "(cells without geometry fall back to sh); sh: the accumulated intensity "
                  "against the clamped cosine around -n (seed 002)",
                  true}};
  graph::set_size_rule(info, "diffuse", graph::viewport_size());
  info.validate = [](graph::PassCheck& check) { contracts::check_clipmap_info_size(check); };
  registry.add(std::move(info), [] { return std::make_unique<LookupPass>(); });
}

}  // namespace voxgi::passes::lpv
