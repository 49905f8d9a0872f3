// dvs.voxel_lighting: per-voxel direct lighting (Villegas, deferred voxel shading §2). Reads the
// voxelized albedo, normal and emission clipmaps and writes the radiance clipmap of the voxel
// contract (rgb outgoing diffuse radiance, a opacity), and with the faces each face group's
// share of that light (light_shares, for vct.filter). Only lights or voxels changing make it
// run again: when the voxelization skipped and no light moved, it skips too, and when only
// lights changed it re-lights the existing voxels without a revoxelization.

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
#include "passes/dvs/dvs_pipeline.hpp"
#include "passes/dvs/passes.hpp"

namespace voxgi::passes::dvs {
namespace {

enum Occlusion : uint32_t { kOcclusionNone = 0, kOcclusionShadowMap = 1, kOcclusionVoxelRays = 2 };
enum Cosine : uint32_t { kCosinePlane = 0, kCosineNormalWeighted = 1 };

struct LightingPush {
  uint32_t size[3];
  uint32_t occlusion;
  float shadow_kappa;
  float shadow_bias;
  uint32_t shadow_slots;
  uint32_t max_steps;
  uint32_t cosine;
};

class VoxelLightingPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    has_emission_ = ctx.has("emission");
    has_shadow_maps_ = ctx.has("shadow_maps") && ctx.has("shadow_matrices");
    has_direct_ = ctx.has("direct");
    has_faces_ = ctx.has("faces");
    has_light_shares_ = has_faces_ && ctx.has("light_shares");
    // The shares are kept for the bounces as the radiance is (validate_voxel_lighting).
    std::vector<gpu::Binding> bindings = {
        {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {6, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0},
    };
    if (has_emission_) bindings.push_back({3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    if (has_shadow_maps_) {
      bindings.push_back({4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      bindings.push_back({5, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0});
    }
    if (has_direct_) bindings.push_back({7, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
    if (has_faces_) bindings.push_back({8, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    if (has_light_shares_) bindings.push_back({9, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
    if (has_light_shares_ && has_direct_) {
      bindings.push_back({10, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
    }
    pipeline_.emplace(graph::make_pass_compute(
        ctx, "dvs/voxel_lighting.comp", bindings, sizeof(LightingPush), true,
        {{"HAS_EMISSION", has_emission_ ? "1" : "0"},
         {"HAS_SHADOW_MAPS", has_shadow_maps_ ? "1" : "0"},
         {"HAS_DIRECT_COPY", has_direct_ ? "1" : "0"},
         {"HAS_FACES", has_faces_ ? "1" : "0"},
         {"HAS_LIGHT_SHARES", has_light_shares_ ? "1" : "0"}}));
    inputs_.forget();
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    const graph::FrameInfo& frame = ctx.frame();
    if (frame.first_frame || frame.lights_changed || ctx.params_changed() || inputs_.changed(ctx)) {
      return {};
    }
    return "voxels, lights and shadow maps unchanged";
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    gpu::Context& gpu = ctx.gpu();
    const VkSampler nearest = gpu.sampler(gpu::SamplerKind::NearestClamp);
    const graph::BoundResource& out = ctx.resource("radiance");
    const graph::BoundResource& albedo = ctx.resource("albedo");
    const graph::BoundResource& normal = ctx.resource("normal");

    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("clipmap_info").buffer);
    writer.sampled_image(1, albedo.view, albedo.layout, nearest);
    writer.sampled_image(2, normal.view, normal.layout, nearest);
    writer.storage_image(6, storage_view(out), out.layout);
    if (has_emission_) {
      const graph::BoundResource& emission = ctx.resource("emission");
      writer.sampled_image(3, emission.view, emission.layout, nearest);
    }
    if (has_faces_) {
      const graph::BoundResource& faces = ctx.resource("faces");
      writer.sampled_image(8, faces.view, faces.layout, nearest);
    }
    if (has_light_shares_) {
      const graph::BoundResource& shares = ctx.resource("light_shares");
      writer.storage_image(9, storage_view(shares), shares.layout);
      if (has_direct_) {
        const graph::BoundResource& direct_shares = ctx.resource("direct_shares");
        writer.storage_image(10, storage_view(direct_shares), direct_shares.layout);
      }
    }
    if (has_direct_) {
      const graph::BoundResource& direct = ctx.resource("direct");
      writer.storage_image(7, storage_view(direct), direct.layout);
    }

    const VkExtent3D extent = graph::bound_extent(*out.info);
    LightingPush push{};
    push.size[0] = extent.width;
    push.size[1] = extent.height;
    push.size[2] = extent.depth;
    const std::string& occlusion = ctx.choice("occlusion");
    push.occlusion = occlusion == "voxel_rays"   ? kOcclusionVoxelRays
                     : occlusion == "shadow_map" ? kOcclusionShadowMap
                                                 : kOcclusionNone;
    push.shadow_kappa = static_cast<float>(ctx.number("shadow_kappa"));
    push.shadow_bias = static_cast<float>(ctx.number("shadow_bias"));
    push.max_steps = static_cast<uint32_t>(ctx.integer("shadow_max_steps"));
    push.cosine = ctx.choice("cosine") == "normal_weighted" ? kCosineNormalWeighted : kCosinePlane;
    if (has_shadow_maps_) {
      push.shadow_slots = contracts::write_shadow_inputs(ctx, writer, 4, 5);
    }
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    graph::bind_scene_set(ctx, *pipeline_);
    pipeline_->push_constants(cmd, push);
    dispatch_over_volume(cmd, extent);
    inputs_.remember(ctx);
  }

 private:
  bool has_emission_ = false;
  bool has_shadow_maps_ = false;
  bool has_direct_ = false;
  bool has_faces_ = false;
  bool has_light_shares_ = false;
  graph::InputVersions inputs_{
      {"clipmap_info", "albedo", "normal", "emission", "faces", "shadow_maps", "shadow_matrices"}};
  std::optional<gpu::ComputePipeline> pipeline_;
};

void validate_voxel_lighting(graph::PassCheck& check) {
  contracts::check_clipmap_info_size(check);
  graph::check_same_clipmap_layout(
      check, "radiance",
      {"albedo", "normal", "emission", "direct", "faces", "light_shares", "direct_shares"});
  contracts::check_light_shares_have_faces(check);
  if (check.has("light_shares") && check.has("direct") != check.has("direct_shares")) {
    check.slot_error("direct_shares",
                     "bind it exactly when 'direct' is (the bounces need the direct light's "
                     "shares with the direct light)");
  }
}

}  // namespace

void register_voxel_lighting(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "dvs.voxel_lighting";
  info.doc =
      "Deferred voxel shading: per-voxel direct lighting (point, spot, directional) with the "
      "plane's cosine or the seed's normal-weighted attenuation, shadow-map or soft voxel-ray "
      "occlusion, plus emission";
  info.inputs = {
      contracts::clipmap_info_input(),
      clipmap_input("albedo", "voxel albedo (rgb) and opacity (a)"),
      clipmap_input("normal", "voxel averaged normal (xyz), occupancy (w)"),
      clipmap_input("emission", "voxel emitted radiance; unbound: none", true),
      contracts::voxel_faces_input(),
      contracts::shadow_maps_input("from common.shadow_maps (occlusion = shadow_map)"),
      contracts::shadow_matrices_input("from common.shadow_maps (occlusion = shadow_map)"),
  };
  info.outputs = {
      radiance_volume_output("radiance",
                             "voxel radiance: rgb outgoing diffuse radiance, a opacity (mip 0)"),
      radiance_volume_output("direct", "the same values, kept for dvs.voxel_bounce", true),
      contracts::voxel_light_shares_output(),
      {"direct_shares",
       graph::kinds(graph::ResourceKind::Clipmap),
       graph::Access::StorageWrite,
       graph::kStageCompute,
       {contracts::kVoxelLightSharesFormat},
       true,
       "the same light shares, kept for dvs.voxel_bounce (with direct and light_shares)"},
  };
  info.params = {
      {"cosine",
       graph::ParamType::Enum,
       0.0,
       0.0,
       0.0,
       {"plane", "normal_weighted"},
       "cosine of each surface towards a light: plane, max(N.L, 0) of the voxel's (or face "
       "group's) plane, or normal_weighted, the seed's per-axis attenuation (§2.1), which "
       "lights tilted planes as axis faces",
       true},
      {"occlusion",
       graph::ParamType::Enum,
       2.0,
       0.0,
       0.0,
       {"none", "shadow_map", "voxel_rays"},
       "light occlusion: none, the shadow maps, or soft voxel ray casting",
       true},
      {"shadow_kappa",
       graph::ParamType::Float,
       8.0,
       0.0,
       1e4,
       {},
       "voxel rays: occlusion gained per opaque voxel crossed at one voxel of distance (kappa)",
       true},
      {"shadow_bias",
       graph::ParamType::Float,
       1.0,
       0.0,
       8.0,
       {},
       "voxel rays: start of shadow rays off the voxel's surface point, in voxels (shadow-map "
       "lookups start two shadow-map texels off it)",
       true},
      {"shadow_max_steps",
       graph::ParamType::Int,
       512.0,
       1.0,
       8192.0,
       {},
       "voxel rays: most samples per ray (half a voxel apart)",
       true},
  };
  graph::set_size_rule(info, "radiance", graph::same_layout_as("albedo"));
  graph::set_size_rule(info, "direct", graph::same_layout_as("albedo"));
  graph::set_size_rule(info, "light_shares", graph::same_layout_as("albedo"));
  graph::set_size_rule(info, "direct_shares", graph::same_layout_as("albedo"));
  info.may_skip = true;
  info.validate = validate_voxel_lighting;
  registry.add(std::move(info), [] { return std::make_unique<VoxelLightingPass>(); });
}

}  // namespace voxgi::passes::dvs
