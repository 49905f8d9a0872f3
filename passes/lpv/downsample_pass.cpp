// lpv.downsample: the injected LPV and the geometry volume on every octree level: level 0 from
// lpv.inject's fixed-point sums and the voxels, each further level the mean of its children
// (shaders/lpv/downsample.comp). With one octree level (the uniform LPV) only level 0. Skips
// when the injection, the voxels and its parameters did not change.

#include <memory>
#include <optional>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"
#include "passes/contracts/voxel_clipmap.hpp"
#include "passes/contracts/voxel_volumes.hpp"
#include "passes/lpv/lpv_layout.hpp"
#include "passes/lpv/passes.hpp"

namespace voxgi::passes::lpv {
namespace {

struct DownsamplePush {
  uint32_t mode;
  uint32_t level;
  uint32_t pad[2];
};

constexpr uint32_t kLocal = 64;

class DownsamplePass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    occlusion_ = ctx.flag("occlusion");
    std::vector<gpu::Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                          {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0}};
    if (occlusion_) {
      bindings.push_back({3, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      bindings.push_back({4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    }
    pipeline_.emplace(graph::make_pass_compute(ctx, "lpv/downsample.comp", bindings,
                                               sizeof(DownsamplePush), false,
                                               {{"HAS_OCCLUSION", occlusion_ ? "1" : "0"}}));
    versions_.forget();
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (ctx.params_changed()) return {};
    return !versions_.changed(ctx) ? "injection and voxels unchanged" : std::string();
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    const VkSampler nearest = ctx.gpu().sampler(gpu::SamplerKind::NearestClamp);
    const graph::BoundResource& albedo = ctx.resource("albedo");
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("clipmap_info").buffer)
        .storage_buffer(1, *ctx.resource("injected").buffer)
        .storage_buffer(2, *ctx.resource("levels").buffer);
    if (occlusion_) {
      const graph::BoundResource& normal = ctx.resource("normal");
      writer.sampled_image(3, albedo.view, albedo.layout, nearest)
          .sampled_image(4, normal.view, normal.layout, nearest);
    }
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    const graph::ResourceInfo& clipmap = *albedo.info;
    DownsamplePush push{0, 0, {}};
    pipeline_->push_constants(cmd, push);
    vkCmdDispatch(cmd, graph::workgroups(lpv_cell_count(clipmap), kLocal), 1, 1);
    const auto octree_levels = static_cast<uint32_t>(ctx.integer("octree_levels"));
    for (uint32_t level = 1; level < octree_levels; ++level) {
      ctx.barrier_within_pass("levels");
      push = {1, level, {}};
      pipeline_->push_constants(cmd, push);
      const uint64_t cells =
          lpv_octree_cell_count(clipmap, level + 1) - lpv_octree_cell_count(clipmap, level);
      vkCmdDispatch(cmd, graph::workgroups(cells, kLocal), 1, 1);
    }
    versions_.remember(ctx);
  }

 private:
  bool occlusion_ = false;
  std::optional<gpu::ComputePipeline> pipeline_;
  graph::InputVersions versions_{{"clipmap_info", "injected", "albedo", "normal"}};
};

}  // namespace

void register_downsample(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "lpv.downsample";
  info.doc =
      "LPV levels: decodes the injection and builds the geometry volume from the voxels at "
      "level 0 (seed 002's GVInject), then each octree level as the mean of its children "
      "(LPVDownsample, GVDownsample)";
  info.inputs = {
      contracts::clipmap_info_input(),
      graph::compute_buffer_slot("injected", graph::Access::StorageRead,
                                 "lpv.inject's fixed-point intensities"),
      graph::sampled_clipmap_input(
          "albedo", "voxel opacity (a): the LPV has one cell per voxel of this clipmap", false,
          {contracts::kVoxelAlbedoFormat, VK_FORMAT_R16G16B16A16_SFLOAT}),
      graph::sampled_clipmap_input("normal", "voxel normals, for the blocking potential", false,
                                   {contracts::kVoxelNormalFormat, VK_FORMAT_R32G32B32A32_SFLOAT}),
  };
  info.outputs = {
      graph::compute_buffer_slot(
          "levels", graph::Access::StorageWrite,
          "per cell of every octree level: the injected SH, the index mark and the geometry "
          "(lpv/cells.glsl)"),
  };
  info.params = {
      octree_levels_param(),
      {"occlusion",
       graph::ParamType::Bool,
       1.0,
       0.0,
       1.0,
       {},
       "build the geometry volume (without it propagation is not blocked)",
       false},
  };
  graph::set_size_rule(info, "levels", lpv_buffer_size(LpvBuffer::Levels, "albedo"));
  info.may_skip = true;
  info.validate = [](graph::PassCheck& check) {
    contracts::check_clipmap_info_size(check);
    graph::check_same_clipmap_layout(check, "albedo", {"normal"});
    check_octree_levels(check, "albedo");
    check_lpv_buffer(check, LpvBuffer::Injected, "injected", "albedo");
    check_lpv_buffer(check, LpvBuffer::Levels, "levels", "albedo");
  };
  registry.add(std::move(info), [] { return std::make_unique<DownsamplePass>(); });
}

}  // namespace voxgi::passes::lpv
