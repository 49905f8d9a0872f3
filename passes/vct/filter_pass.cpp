// vct.filter: turns the radiance clipmap into the filtered volumes the cone tracer samples
// (layout documented at the top of shaders/contracts/cone_trace.glsl): premultiplied radiance and
// opacity, mip 0 of every level made consistent with the finer level it contains, then a full
// mip chain per level. Isotropic mode writes one volume; anisotropic mode six directional
// volumes built by front-to-back compositing along each axis (Crassin; seed 001 section 3).

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "passes/contracts/voxel_volumes.hpp"
#include "passes/vct/passes.hpp"
#include "passes/vct/vct_pipeline.hpp"

namespace voxgi::passes::vct {
namespace {

struct FilterPush {
  int32_t stage;  // 0: mip 0 of one level, 1: one mip of all levels
  int32_t level;
  int32_t mip;
  int32_t pad;
};

constexpr uint32_t kLocal = 4;
constexpr uint32_t kNormalBinding = 14;
constexpr uint32_t kFacesBinding = 15;
constexpr uint32_t kLightSharesBinding = 16;
constexpr uint32_t kFacingBinding = 17;  // src, dst of facing_pos, then of facing_neg

class FilterPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    anisotropic_ = ctx.choice("mode") == "anisotropic";
    volume_slots_.clear();
    if (anisotropic_) {
      for (const char* slot : contracts::kDirectionalSlots) volume_slots_.push_back(slot);
    } else {
      volume_slots_.push_back(contracts::kFilteredSlot);
    }
    level_coverage_ = ctx.has("normal");
    face_facing_ = ctx.has("faces");
    light_shares_ = face_facing_ && anisotropic_ && ctx.has("light_shares");
    front_light_ = anisotropic_ && face_facing_ && contracts::front_light_bound(ctx);
    std::vector<gpu::Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                          {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0}};
    for (uint32_t v = 0; v < volume_slots_.size(); ++v) {
      bindings.push_back({2 + 2 * v, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
      bindings.push_back({3 + 2 * v, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
    }
    if (level_coverage_) {
      bindings.push_back({kNormalBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    }
    if (face_facing_) {
      bindings.push_back({kFacesBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    }
    if (light_shares_) {
      bindings.push_back({kLightSharesBinding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    }
    if (front_light_) {
      for (uint32_t b = 0; b < 4; ++b) {
        bindings.push_back({kFacingBinding + b, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 0});
      }
    }
    output_slots_ = volume_slots_;
    if (front_light_) {
      for (const char* slot : contracts::kFacingSlots) output_slots_.push_back(slot);
    }
    pipeline_.emplace(graph::make_pass_compute(ctx, "vct/filter.comp", bindings, sizeof(FilterPush),
                                               false,
                                               {{"ANISOTROPIC", anisotropic_ ? "1" : "0"},
                                                {"LEVEL_COVERAGE", level_coverage_ ? "1" : "0"},
                                                {"FACE_FACING", face_facing_ ? "1" : "0"},
                                                {"LIGHT_SHARES", light_shares_ ? "1" : "0"},
                                                {"FRONT_LIGHT", front_light_ ? "1" : "0"}}));
    versions_.forget();
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (ctx.params_changed()) return {};
    return !versions_.changed(ctx) ? "radiance volume unchanged" : std::string();
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const graph::BoundResource& info = ctx.resource("clipmap_info");
    const graph::BoundResource& radiance = ctx.resource("radiance");
    const uint32_t r = radiance.info->extent.width;
    const uint32_t levels = std::max(1u, radiance.info->clipmap_levels);
    uint32_t mips = full_mip_count_of(r);
    for (const std::string& slot : output_slots_) {
      mips = std::min(mips, ctx.info(slot).mip_levels);
    }
    pipeline_->bind(cmd);
    auto push = [&](uint32_t src_mip, uint32_t dst_mip) {
      gpu::DescriptorWriter writer;
      writer.storage_buffer(0, *info.buffer);
      writer.sampled_image(1, radiance.view, radiance.layout,
                           ctx.gpu().sampler(gpu::SamplerKind::NearestClamp));
      if (level_coverage_) {
        const graph::BoundResource& normal = ctx.resource("normal");
        writer.sampled_image(kNormalBinding, normal.view, normal.layout,
                             ctx.gpu().sampler(gpu::SamplerKind::NearestClamp));
      }
      if (face_facing_) {
        const graph::BoundResource& faces = ctx.resource("faces");
        writer.sampled_image(kFacesBinding, faces.view, faces.layout,
                             ctx.gpu().sampler(gpu::SamplerKind::NearestClamp));
      }
      if (light_shares_) {
        const graph::BoundResource& shares = ctx.resource("light_shares");
        writer.sampled_image(kLightSharesBinding, shares.view, shares.layout,
                             ctx.gpu().sampler(gpu::SamplerKind::NearestClamp));
      }
      for (uint32_t v = 0; v < volume_slots_.size(); ++v) {
        const graph::BoundResource& out = ctx.resource(volume_slots_[v]);
        writer.storage_image(2 + 2 * v, out.image->view(src_mip), out.layout);
        writer.storage_image(3 + 2 * v, out.image->view(dst_mip), out.layout);
      }
      if (front_light_) {
        for (uint32_t f = 0; f < 2; ++f) {
          const graph::BoundResource& out = ctx.resource(contracts::kFacingSlots[f]);
          writer.storage_image(kFacingBinding + 2 * f, out.image->view(src_mip), out.layout);
          writer.storage_image(kFacingBinding + 2 * f + 1, out.image->view(dst_mip), out.layout);
        }
      }
      writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    };
    auto barrier = [&] {
      for (const std::string& slot : output_slots_) ctx.barrier_within_pass(slot);
    };
    push(0, 0);
    for (uint32_t level = 0; level < levels; ++level) {
      pipeline_->push_constants(cmd, FilterPush{0, static_cast<int32_t>(level), 0, 0});
      const uint32_t g = graph::workgroups(r, kLocal);
      vkCmdDispatch(cmd, g, g, g);
      barrier();
    }
    for (uint32_t mip = 1; mip < mips; ++mip) {
      push(mip - 1, mip);
      const uint32_t rm = std::max(1u, r >> mip);
      pipeline_->push_constants(cmd, FilterPush{1, 0, static_cast<int32_t>(mip), 0});
      vkCmdDispatch(cmd, graph::workgroups(rm, kLocal), graph::workgroups(rm, kLocal),
                    graph::workgroups(rm * levels, kLocal));
      barrier();
    }
    versions_.remember(ctx);
  }

 private:
  static uint32_t full_mip_count_of(uint32_t r) {
    uint32_t count = 1;
    while ((r >> count) > 0) ++count;
    return count;
  }

  bool anisotropic_ = true;
  bool level_coverage_ = false;
  bool face_facing_ = false;
  bool light_shares_ = false;
  bool front_light_ = false;
  std::vector<std::string> volume_slots_;
  std::vector<std::string> output_slots_;  // the volumes and, front light, the facing volumes
  std::optional<gpu::ComputePipeline> pipeline_;
  graph::InputVersions versions_{{"clipmap_info", "radiance", "normal", "faces", "light_shares"}};
};

void validate_filter(graph::PassCheck& check) {
  contracts::check_clipmap_info_size(check);
  if (check.choice("mode") == "isotropic") {
    if (!check.has(contracts::kFilteredSlot)) {
      check.param_error("mode", "mode 'isotropic' needs the output slot 'filtered' bound");
    }
  } else if (const std::string missing = unbound_directional_slots(check); !missing.empty()) {
    check.param_error("mode",
                      "mode 'anisotropic' needs the output slots pos_x, neg_x, pos_y, neg_y, "
                      "pos_z, neg_z bound; unbound: " +
                          missing);
  }
  contracts::validate_front_light_slots(check);
  if (contracts::front_light_bound(check) && !check.has("faces")) {
    check.slot_error(contracts::kFacingSlots[0],
                     "the front-light mode needs the voxels' faces: bind the input 'faces'");
  }
  graph::check_same_clipmap_layout(
      check, "radiance",
      {contracts::kFilteredSlot, "normal", "faces", "light_shares", "pos_x", "neg_x", "pos_y",
       "neg_y", "pos_z", "neg_z", contracts::kFacingSlots[0], contracts::kFacingSlots[1]});
}

graph::SlotSpec filtered_output(const char* name, std::string doc) {
  return {name,
          graph::kinds(graph::ResourceKind::Clipmap),
          graph::Access::StorageReadWrite,  // coarser levels read the finer ones just written
          graph::kStageCompute,
          {VK_FORMAT_R16G16B16A16_SFLOAT},
          true,
          std::move(doc)};
}

}  // namespace

void register_filter(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "vct.filter";
  info.doc =
      "Filters the radiance clipmap into the cone tracer's volumes: premultiplied radiance and "
      "opacity with per-level mips, levels kept consistent; isotropic or six anisotropic "
      "directions";
  info.inputs = {
      contracts::clipmap_info_input(),
      graph::sampled_clipmap_input("radiance",
                                   "radiance clipmap (rgb outgoing radiance, a opacity) from "
                                   "vct.inject or dvs.voxel_lighting; only mip 0 is read",
                                   false, {VK_FORMAT_R16G16B16A16_SFLOAT}),
      graph::sampled_clipmap_input(
          "normal",
          "voxel normals (common.voxelize); with them, a coarser level's voxels that no finer "
          "level covers hold a surface as thin as the finer level's filter would (anisotropic: "
          "opaque across a plane, 1/2^level of it along)",
          true, {VK_FORMAT_R16G16B16A16_SFLOAT}),
      graph::sampled_clipmap_input(
          "faces",
          "the voxels' surfaces grouped by facing (common.voxelize); with them, a voxel's light "
          "enters each directional volume as its surfaces show it that way (anisotropic)",
          true, {contracts::kVoxelFacesFormat}),
      graph::sampled_clipmap_input(
          "light_shares",
          "per face group its share of the voxel's light (the injection's light_shares); with "
          "the faces, each group sends its own light; unbound: the voxel's groups are taken as "
          "lit alike",
          true, {contracts::kVoxelLightSharesFormat})};
  info.outputs = {filtered_output("filtered", "isotropic filtered volume (mode isotropic)")};
  const char* directions[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  for (size_t i = 0; i < contracts::kDirectionalSlots.size(); ++i) {
    info.outputs.push_back(
        filtered_output(contracts::kDirectionalSlots[i],
                        std::string("directional volume seen by cones travelling ") +
                            directions[i] + " (mode anisotropic)"));
  }
  info.outputs.push_back(filtered_output(
      contracts::kFacingSlots[0],
      "front-light mode (with facing_neg and the faces): per axis the share of the opacity "
      "lying across it for cones travelling +X, +Y, +Z (channels x, y, z); the six volumes "
      "then hold only the light of the surfaces facing each direction"));
  info.outputs.push_back(filtered_output(contracts::kFacingSlots[1],
                                         "front-light mode: as facing_pos for -X, -Y, -Z"));
  info.params = {{"mode",
                  graph::ParamType::Enum,
                  1.0,
                  0.0,
                  0.0,
                  {"isotropic", "anisotropic"},
                  "isotropic: one box-filtered volume; anisotropic: six directional volumes "
                  "(front-to-back along each axis), needs the six pos_x..neg_z outputs",
                  false}};
  // The volumes take the radiance clipmap's layout, with full mip chains.
  for (const graph::SlotSpec& slot : std::vector<graph::SlotSpec>(info.outputs)) {
    graph::set_size_rule(info, slot.name, graph::same_layout_as("radiance", true));
  }
  info.may_skip = true;
  info.validate = validate_filter;
  registry.add(std::move(info), [] { return std::make_unique<FilterPass>(); });
}

}  // namespace voxgi::passes::vct
