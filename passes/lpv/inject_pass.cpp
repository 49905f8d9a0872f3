// lpv.inject: the reflective shadow maps' texels (and emissive voxels) as virtual point lights
// into the LPV cells, in fixed point (shaders/lpv/inject.comp derives the flux and the scale).
// Four dispatches: clear, largest contribution, RSM texels, emissive voxels. Skips when none of
// its inputs was rewritten.

#include <memory>
#include <optional>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "passes/lpv/lpv_layout.hpp"
#include "passes/lpv/passes.hpp"

namespace voxgi::passes::lpv {
namespace {

struct InjectPush {
  uint32_t mode;
  uint32_t stride;
  uint32_t injected_edge;
  uint32_t layers;
  uint32_t contributions;
  uint32_t words;
  float normal_offset;
  uint32_t pad;
};

constexpr uint32_t kLocal = 64;

// Voxel normal and emission are read as floating-point RGBA.
const std::vector<VkFormat> kFloatRgba = {VK_FORMAT_R16G16B16A16_SFLOAT,
                                          VK_FORMAT_R32G32B32A32_SFLOAT};

class InjectPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    has_emission_ = ctx.has("emission");
    std::vector<gpu::Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                          {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                          {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                          {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                          {4, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0}};
    if (has_emission_) {
      bindings.push_back({5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      bindings.push_back({6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    }
    pipeline_.emplace(graph::make_pass_compute(ctx, "lpv/inject.comp", bindings, sizeof(InjectPush),
                                               false,
                                               {{"HAS_EMISSION", has_emission_ ? "1" : "0"}}));
    versions_.forget();
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (ctx.params_changed()) return {};
    return !versions_.changed(ctx) ? "reflective shadow maps and voxels unchanged" : std::string();
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const VkSampler nearest = ctx.gpu().sampler(gpu::SamplerKind::NearestClamp);
    const graph::BoundResource& flux = ctx.resource("rsm_flux");
    const graph::BoundResource& normal = ctx.resource("rsm_normal");
    const graph::BoundResource& position = ctx.resource("rsm_position");
    const graph::BoundResource& injected = ctx.resource("injected");
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("clipmap_info").buffer)
        .sampled_image(1, flux.view, flux.layout, nearest)
        .sampled_image(2, normal.view, normal.layout, nearest)
        .sampled_image(3, position.view, position.layout, nearest)
        .storage_buffer(4, *injected.buffer);
    const uint64_t cells = lpv_cell_count(*ctx.resource("voxel_normal").info);
    if (has_emission_) {
      const graph::BoundResource& voxel_normal = ctx.resource("voxel_normal");
      const graph::BoundResource& emission = ctx.resource("emission");
      writer.sampled_image(5, voxel_normal.view, voxel_normal.layout, nearest)
          .sampled_image(6, emission.view, emission.layout, nearest);
    }
    const uint32_t stride = static_cast<uint32_t>(ctx.integer("stride"));
    const uint32_t edge = std::max(1u, flux.info->extent.width / stride);
    const uint64_t texels = uint64_t(edge) * edge * flux.info->array_layers;
    const uint64_t emitters =
        has_emission_ ? lpv_voxel_count(*ctx.resource("voxel_normal").info) : 0;
    InjectPush push{0,
                    stride,
                    edge,
                    flux.info->array_layers,
                    static_cast<uint32_t>(texels + emitters),
                    static_cast<uint32_t>(cells * kCoefficientsPerCell),
                    static_cast<float>(ctx.number("normal_offset")),
                    0};
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    const auto dispatch = [&](uint32_t mode, uint64_t invocations) {
      push.mode = mode;
      pipeline_->push_constants(cmd, push);
      if (invocations > 0) vkCmdDispatch(cmd, graph::workgroups(invocations, kLocal), 1, 1);
      ctx.barrier_within_pass("injected");
    };
    dispatch(0, cells * kCoefficientsPerCell);
    dispatch(1, texels + emitters);
    dispatch(2, texels);
    dispatch(3, emitters);
    versions_.remember(ctx);
  }

 private:
  bool has_emission_ = false;
  std::optional<gpu::ComputePipeline> pipeline_;
  graph::InputVersions versions_{
      {"clipmap_info", "rsm_flux", "rsm_normal", "rsm_position", "voxel_normal", "emission"}};
};

}  // namespace

void register_inject(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "lpv.inject";
  info.doc =
      "Reflective-shadow-map texels and emissive voxels as Lambertian virtual point lights into "
      "the LPV cells (seed 002's LPVInject), deterministic fixed point";
  info.inputs = {
      contracts::clipmap_info_input(),
      graph::sampled_2d_input("rsm_flux", "lpv.rsm's reflected flux", false,
                              {kRsmFluxFormat, VK_FORMAT_R32G32B32A32_SFLOAT}),
      graph::sampled_2d_input("rsm_normal", "lpv.rsm's normals", false,
                              {kRsmNormalFormat, VK_FORMAT_R32G32B32A32_SFLOAT}),
      graph::sampled_2d_input("rsm_position", "lpv.rsm's world positions", false,
                              {kRsmPositionFormat}),
      graph::sampled_clipmap_input(
          "voxel_normal",
          "voxel normals: the LPV has one cell per voxel of this clipmap, and "
          "emissive voxels emit along them",
          false, kFloatRgba),
      graph::sampled_clipmap_input(
          "emission", "voxel emitted radiance; unbound: no emitters inject", true, kFloatRgba),
  };
  info.outputs = {graph::compute_buffer_slot("injected", graph::Access::StorageWrite,
                                             "fixed-point SH intensity per cell (lpv/cells.glsl)")};
  info.params = {
      {"stride",
       graph::ParamType::Int,
       1.0,
       1.0,
       64.0,
       {},
       "inject every stride-th RSM texel in x and y, each standing for stride^2 texels (seed "
       "002: 4 on 1024^2 maps)",
       true},
      {"normal_offset",
       graph::ParamType::Float,
       1.0,
       0.0,
       2.0,
       {},
       "distance of a virtual point light from its surface along the normal, in cells (seed "
       "002: 0.5); 1 puts it in the next cell, so its surface's own cell cannot stop its light",
       true},
  };
  graph::set_size_rule(info, "injected", lpv_buffer_size(LpvBuffer::Injected, "voxel_normal"));
  info.may_skip = true;
  info.validate = [](graph::PassCheck& check) {
    contracts::check_clipmap_info_size(check);
    graph::check_same_clipmap_layout(check, "voxel_normal", {"emission"});
    check_lpv_buffer(check, LpvBuffer::Injected, "injected", "voxel_normal");
  };
  registry.add(std::move(info), [] { return std::make_unique<InjectPass>(); });
}

}  // namespace voxgi::passes::lpv
