// dvs.voxel_bounce: one indirect diffuse bounce per voxel by cone tracing the filtered
// radiance volume from each voxel's normal hemisphere (Villegas, "Voxel Global Illumination").
// Writes direct + albedo/pi * E into the radiance clipmap, which vct.filter filters again for
// the next bounce or the final gather, and with the faces the light shares of that radiance
// (the direct light's as dvs.voxel_lighting wrote them, the gathered light by area).
// graphs/dvs.json chains K of them (docs/dvs.md).

#include <memory>
#include <optional>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "passes/contracts/filtered_volumes.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "passes/contracts/voxel_volumes.hpp"
#include "passes/dvs/dvs_pipeline.hpp"
#include "passes/dvs/passes.hpp"

namespace voxgi::passes::dvs {
namespace {

using graph::Access;
using graph::ResourceKind;

struct BouncePush {
  uint32_t size[3];
  int32_t cones;
  float step_factor;
  float max_distance;
  float normal_offset;
  float start_offset;
};

class VoxelBouncePass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    anisotropic_ =
        ctx.has(contracts::kDirectionalSlots[0]);  // all six or none (validate_voxel_bounce)
    has_light_shares_ = ctx.has("light_shares");
    front_light_ = anisotropic_ && contracts::front_light_bound(ctx);
    std::vector<gpu::Binding> bindings = {
        {0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
        {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0,
         contracts::volume_array_size(anisotropic_, front_light_)},
        {2, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0},
        {5, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0},
    };
    if (has_light_shares_) {
      bindings.push_back({6, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      bindings.push_back({7, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      bindings.push_back({8, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
    }
    const char* volumes = anisotropic_ ? contracts::kDirectionalSlots[0] : contracts::kFilteredSlot;
    pipeline_.emplace(graph::make_pass_compute(
        ctx, "dvs/voxel_bounce.comp", bindings, sizeof(BouncePush), false,
        {{"VCT_ANISOTROPIC", anisotropic_ ? "1" : "0"},
         contracts::front_light_define(front_light_),
         contracts::unwrapped_windows_define(ctx.info(volumes).clipmap_levels),
         contracts::clipmap_levels_define(ctx.info(volumes).clipmap_levels),
         contracts::refine_levels_define(ctx.integer("refine")),
         {"HAS_LIGHT_SHARES", has_light_shares_ ? "1" : "0"}}));
    // The volumes' sampler of the cone-trace contract (no anisotropic filtering): a mipmapped
    // sampler with anisotropy took extra taps around every explicit-LOD sample on lavapipe,
    // which widened each footprint and left the voxel bounces at 0.73 of the path tracer's on
    // the Cornell box (docs/error-budget.md, thirteenth round).
    if (!sampler_) sampler_ = std::make_unique<contracts::VolumeSampler>(ctx.gpu());
    inputs_.forget();
  }

  // Every bounce derives from the direct light and the voxels: while those are unchanged the
  // previous result (persistent) is still the answer.
  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (ctx.frame().first_frame || ctx.params_changed() || inputs_.changed(ctx)) {
      return {};
    }
    return "direct light and voxels unchanged";
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    gpu::Context& gpu = ctx.gpu();
    const VkSampler nearest = gpu.sampler(gpu::SamplerKind::NearestClamp);
    const VkSampler repeat = sampler_->handle();
    const graph::BoundResource& out = ctx.resource("radiance");

    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("clipmap_info").buffer);
    writer.image_array(1,
                       contracts::filtered_volume_images(ctx, anisotropic_, front_light_, repeat));
    const char* inputs[] = {"albedo", "normal", "direct"};
    for (uint32_t i = 0; i < 3; ++i) {
      const graph::BoundResource& r = ctx.resource(inputs[i]);
      // The normals are also interpolated and wrapped like the volumes (the cones' facing test).
      writer.sampled_image(2 + i, r.view, r.layout, i == 1 ? repeat : nearest);
    }
    writer.storage_image(5, storage_view(out), out.layout);
    if (has_light_shares_) {
      const graph::BoundResource& faces = ctx.resource("faces");
      const graph::BoundResource& direct_shares = ctx.resource("direct_shares");
      const graph::BoundResource& shares = ctx.resource("light_shares");
      writer.sampled_image(6, faces.view, faces.layout, nearest)
          .sampled_image(7, direct_shares.view, direct_shares.layout, nearest)
          .storage_image(8, storage_view(shares), shares.layout);
    }

    const VkExtent3D extent = out.info->extent;
    const BouncePush push{{extent.width, extent.height, extent.depth},
                          ctx.integer("diffuse_cones"),
                          static_cast<float>(ctx.number("step_factor")),
                          contracts::cone_max_distance(ctx.number("max_distance")),
                          static_cast<float>(ctx.number("normal_offset")),
                          static_cast<float>(ctx.number("start_offset"))};
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    pipeline_->push_constants(cmd, push);
    dispatch_over_volume(cmd, extent);
    inputs_.remember(ctx);
  }

 private:
  bool anisotropic_ = false;
  bool has_light_shares_ = false;
  bool front_light_ = false;  // the facing volumes are bound (contracts::kFacingSlots)
  graph::InputVersions inputs_{
      {"clipmap_info", "albedo", "normal", "direct", "faces", "direct_shares"}};
  std::optional<gpu::ComputePipeline> pipeline_;
  std::unique_ptr<contracts::VolumeSampler> sampler_;
};

// One isotropic or six directional volumes, of the voxels' layout.
void validate_voxel_bounce(graph::PassCheck& check) {
  contracts::check_clipmap_info_size(check);
  int directional = 0;
  for (const char* slot : contracts::kDirectionalSlots) directional += check.has(slot) ? 1 : 0;
  const bool isotropic = check.has(contracts::kFilteredSlot);
  if (!(directional == 6 && !isotropic) && !(directional == 0 && isotropic)) {
    check.slot_error(contracts::kFilteredSlot,
                     "bind either 'filtered' (isotropic) or all six of pos_x, neg_x, pos_y, "
                     "neg_y, pos_z, neg_z (anisotropic) from vct.filter; " +
                         std::to_string(directional) + " directional volume(s) and " +
                         (isotropic ? "'filtered'" : "no 'filtered'") + " are bound");
  }
  contracts::validate_front_light_slots(check);
  graph::check_same_clipmap_layout(
      check, "radiance",
      {"albedo", "normal", "direct", "faces", "direct_shares", "light_shares",
       contracts::kFacingSlots[0], contracts::kFacingSlots[1]});
  contracts::check_light_shares_have_faces(check);
  if (check.has("light_shares") && !check.has("direct_shares")) {
    check.slot_error("light_shares",
                     "needs the direct_shares input bound (the direct light's shares)");
  }
}

}  // namespace

void register_voxel_bounce(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "dvs.voxel_bounce";
  info.doc =
      "One indirect diffuse bounce per voxel: hemisphere cones around the voxel normal on the "
      "filtered radiance volume; writes direct + albedo/pi * irradiance";
  info.inputs = {
      contracts::clipmap_info_input(),
      contracts::filtered_volume_input(contracts::kFilteredSlot,
                                       "isotropic filtered volume from vct.filter (or bind the six "
                                       "directional volumes)"),
  };
  const char* directions[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  for (size_t i = 0; i < 6; ++i) {
    info.inputs.push_back(contracts::filtered_volume_input(
        contracts::kDirectionalSlots[i], std::string("directional volume for cones travelling ") +
                                             directions[i] + " from vct.filter (anisotropic)"));
  }
  for (const char* slot : contracts::kFacingSlots) {
    info.inputs.push_back(contracts::facing_input(slot));
  }
  info.inputs.push_back(clipmap_input("albedo", "voxel albedo (rgb) and opacity (a)"));
  info.inputs.push_back(clipmap_input("normal", "voxel averaged normal (xyz), occupancy (w)"));
  info.inputs.push_back(clipmap_input("direct", "direct radiance of dvs.voxel_lighting's 'direct'",
                                      false, {VK_FORMAT_R16G16B16A16_SFLOAT}));
  info.inputs.push_back(clipmap_input(
      "faces",
      "the voxels' surfaces grouped by facing (common.voxelize); with direct_shares, the "
      "gathered light goes to the groups by area in the light shares written",
      true, {contracts::kVoxelFacesFormat}));
  info.inputs.push_back(clipmap_input(
      "direct_shares", "dvs.voxel_lighting's light_shares (with faces and light_shares)", true,
      {contracts::kVoxelLightSharesFormat}));
  info.outputs = {
      radiance_volume_output(
          "radiance",
          "voxel radiance with one more bounce: rgb outgoing diffuse radiance, a opacity"),
      contracts::voxel_light_shares_output()};
  info.params = {
      {"diffuse_cones",
       graph::ParamType::Int,
       6.0,
       1.0,
       32.0,
       {},
       "cones over each voxel's hemisphere (equal cosine-weighted cells; weights sum to pi)",
       true},
      {"step_factor",
       graph::ParamType::Float,
       1.0,
       0.05,
       4.0,
       {},
       "beta: step length / cone diameter",
       true},
      contracts::cone_max_distance_param(),
      {"normal_offset",
       graph::ParamType::Float,
       1.0,
       0.0,
       8.0,
       {},
       "cone origin offset along the voxel normal, in voxels of the voxel's level",
       true},
      {"start_offset",
       graph::ParamType::Float,
       1.0,
       0.0,
       8.0,
       {},
       "distance skipped at the start of each cone, in voxels (self-occlusion)",
       true},
      contracts::refine_levels_param(1),
  };
  graph::set_size_rule(info, "radiance", graph::same_layout_as("direct"));
  graph::set_size_rule(info, "light_shares", graph::same_layout_as("direct"));
  info.may_skip = true;
  info.validate = validate_voxel_bounce;
  registry.add(std::move(info), [] { return std::make_unique<VoxelBouncePass>(); });
}

}  // namespace voxgi::passes::dvs
