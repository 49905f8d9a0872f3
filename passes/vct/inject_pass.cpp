// vct.inject: direct light into the radiance clipmap. Each occupied voxel gets the outgoing
// Lambert radiance albedo/pi x sum(light irradiance x cos x shadow-map visibility) plus its
// emission, rgba16f and sanitized (shaders/vct/inject.comp states the rules); with the
// voxelizer's faces, per way its surfaces face, weighted by their area, and (output
// light_shares) each way's share of that light, for vct.filter. The pass skips when none of
// its inputs was rewritten and the lights did not change.

#include <algorithm>
#include <memory>
#include <optional>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "passes/contracts/shadow_data.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "passes/contracts/voxel_volumes.hpp"
#include "passes/vct/passes.hpp"
#include "passes/vct/vct_pipeline.hpp"

namespace voxgi::passes::vct {
namespace {

struct InjectPush {
  uint32_t shadow_slots;
  float normal_offset;
  uint32_t shadows_enabled;
  float pad;
};

constexpr uint32_t kLocal = 4;

// Voxel volumes are read as floating-point RGBA.
const std::vector<VkFormat> kFloatRgba = {VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R16G16B16A16_SFLOAT,
                                          VK_FORMAT_R32G32B32A32_SFLOAT};

class InjectPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    has_shadows_ = ctx.has("shadow_maps") && ctx.has("shadow_matrices");
    has_emission_ = ctx.has("emission");
    has_faces_ = ctx.has("faces");
    has_light_shares_ = has_faces_ && ctx.has("light_shares");
    std::vector<gpu::Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                          {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                          {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
                                          {6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0}};
    if (has_emission_) bindings.push_back({3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    if (has_faces_) bindings.push_back({7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    if (has_light_shares_) bindings.push_back({8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
    if (has_shadows_) {
      bindings.push_back({4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      bindings.push_back({5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0});
    }
    pipeline_.emplace(
        graph::make_pass_compute(ctx, "vct/inject.comp", bindings, sizeof(InjectPush), true,
                                 {{"HAS_SHADOWS", has_shadows_ ? "1" : "0"},
                                  {"HAS_EMISSION", has_emission_ ? "1" : "0"},
                                  {"HAS_FACES", has_faces_ ? "1" : "0"},
                                  {"HAS_LIGHT_SHARES", has_light_shares_ ? "1" : "0"}}));
    versions_.forget();
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (ctx.params_changed() || ctx.frame().lights_changed) return {};
    return !versions_.changed(ctx) ? "voxels, shadow maps and lights unchanged" : std::string();
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    gpu::Context& gpu = ctx.gpu();
    const VkSampler nearest = gpu.sampler(gpu::SamplerKind::NearestClamp);
    const graph::BoundResource& info = ctx.resource("clipmap_info");
    const graph::BoundResource& albedo = ctx.resource("albedo");
    const graph::BoundResource& normal = ctx.resource("normal");
    const graph::BoundResource& out = ctx.resource("radiance");
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *info.buffer)
        .sampled_image(1, albedo.view, albedo.layout, nearest)
        .sampled_image(2, normal.view, normal.layout, nearest)
        .storage_image(6, out.image->view(0), out.layout);
    if (has_emission_) {
      const graph::BoundResource& emission = ctx.resource("emission");
      writer.sampled_image(3, emission.view, emission.layout, nearest);
    }
    if (has_faces_) {
      const graph::BoundResource& faces = ctx.resource("faces");
      writer.sampled_image(7, faces.view, faces.layout, nearest);
    }
    if (has_light_shares_) {
      const graph::BoundResource& shares = ctx.resource("light_shares");
      writer.storage_image(8, shares.image->view(0), shares.layout);
    }
    InjectPush push{0, static_cast<float>(ctx.number("normal_offset")),
                    ctx.flag("shadows") ? 1u : 0u, 0.0f};
    if (has_shadows_) {
      push.shadow_slots = contracts::write_shadow_inputs(ctx, writer, 4, 5);
    }
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    graph::bind_scene_set(ctx, *pipeline_);
    pipeline_->push_constants(cmd, push);
    const VkExtent3D e = out.info->extent;
    vkCmdDispatch(cmd, graph::workgroups(e.width, kLocal), graph::workgroups(e.height, kLocal),
                  graph::workgroups(e.depth, kLocal));
    versions_.remember(ctx);
  }

 private:
  bool has_shadows_ = false;
  bool has_emission_ = false;
  bool has_faces_ = false;
  bool has_light_shares_ = false;
  std::optional<gpu::ComputePipeline> pipeline_;
  graph::InputVersions versions_{
      {"clipmap_info", "albedo", "normal", "emission", "faces", "shadow_maps", "shadow_matrices"}};
};

}  // namespace

void register_inject(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "vct.inject";
  info.doc =
      "Direct light into the radiance clipmap: albedo/pi x light irradiance x cos x shadow-map "
      "visibility per voxel, plus emission";
  info.inputs = {
      contracts::clipmap_info_input(),
      graph::sampled_clipmap_input("albedo", "voxel albedo (rgb linear) and opacity (a)", false,
                                   kFloatRgba),
      graph::sampled_clipmap_input("normal", "voxel averaged normal (xyz; ~0 where faces cancel)",
                                   false, kFloatRgba),
      graph::sampled_clipmap_input("emission", "voxel emitted radiance (rgb); unbound: none", true,
                                   kFloatRgba),
      contracts::voxel_faces_input(),
      contracts::shadow_maps_input("from common.shadow_maps; unbound: lights are unshadowed"),
      contracts::shadow_matrices_input("from common.shadow_maps"),
  };
  info.outputs = {{"radiance",
                   graph::kinds(graph::ResourceKind::Clipmap),
                   graph::Access::StorageWrite,
                   graph::kStageCompute,
                   {VK_FORMAT_R16G16B16A16_SFLOAT},
                   false,
                   "radiance clipmap: rgb outgoing radiance, a opacity (mip 0 written)"},
                  contracts::voxel_light_shares_output()};
  info.params = {
      {"shadows", graph::ParamType::Bool, 1.0, 0.0, 1.0, {}, "test the shadow maps", true},
      {"normal_offset",
       graph::ParamType::Float,
       0.0,
       0.0,
       4.0,
       {},
       "offset of the shadow lookup from the voxel's surface point along its normal (towards "
       "the light for normal-less voxels), in voxels; at least two shadow-map texels",
       true},
  };
  graph::set_size_rule(info, "radiance", graph::same_layout_as("albedo"));
  graph::set_size_rule(info, "light_shares", graph::same_layout_as("albedo"));
  info.may_skip = true;
  info.validate = [](graph::PassCheck& check) {
    contracts::check_clipmap_info_size(check);
    graph::check_same_clipmap_layout(check, "radiance",
                                     {"albedo", "normal", "emission", "faces", "light_shares"});
    contracts::check_light_shares_have_faces(check);
  };
  registry.add(std::move(info), [] { return std::make_unique<InjectPass>(); });
}

}  // namespace voxgi::passes::vct
