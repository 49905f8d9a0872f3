// lpv.merge: the octree levels into one record per level-0 cell, the volume lpv.lookup reads
// (shaders/lpv/merge.comp). With one octree level it copies level 0, so the uniform LPV runs
// the same passes. Skips when the levels and its parameters did not change.

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

struct MergePush {
  uint32_t mode;
  uint32_t octree_levels;
  uint32_t pad[2];
};

constexpr uint32_t kLocal = 64;

class MergePass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    pipeline_.emplace(graph::make_pass_compute(ctx, "lpv/merge.comp",
                                               {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                                {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                                {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0}},
                                               sizeof(MergePush), false));
    versions_.forget();
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (ctx.params_changed()) return {};
    return !versions_.changed(ctx) ? "levels unchanged" : std::string();
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("clipmap_info").buffer)
        .storage_buffer(1, *ctx.resource("levels").buffer)
        .storage_buffer(2, *ctx.resource("radiance").buffer);
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    const MergePush push{ctx.choice("merge") == "shells" ? 1u : 0u,
                         static_cast<uint32_t>(ctx.integer("octree_levels")),
                         {}};
    pipeline_->push_constants(cmd, push);
    vkCmdDispatch(cmd, graph::workgroups(lpv_cell_count(*ctx.resource("voxels").info), kLocal), 1,
                  1);
    versions_.remember(ctx);
  }

 private:
  std::optional<gpu::ComputePipeline> pipeline_;
  graph::InputVersions versions_{{"clipmap_info", "levels", "voxels"}};
};

}  // namespace

void register_merge(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "lpv.merge";
  info.doc =
      "LPV merge (seed 002's LPVMerge): the octree levels into one volume of level-0 cells, "
      "by the index volume (eq. 10) or as distance shells; a copy for the uniform LPV";
  info.inputs = {
      contracts::clipmap_info_input(),
      graph::compute_buffer_slot("levels", graph::Access::StorageRead,
                                 "lpv.propagate's accumulated levels"),
      graph::sampled_clipmap_input("voxels",
                                   "the clipmap whose voxels are the LPV's cells (its layout)"),
  };
  info.outputs = {
      graph::compute_buffer_slot(
          "radiance", graph::Access::StorageWrite,
          "per level-0 cell: SH intensity, stopped flux and the level it took, geometry "
          "(lpv/cells.glsl)"),
  };
  info.params = {octree_levels_param(), merge_param()};
  graph::set_size_rule(info, "radiance", lpv_buffer_size(LpvBuffer::Radiance, "voxels"));
  info.may_skip = true;
  info.validate = [](graph::PassCheck& check) {
    contracts::check_clipmap_info_size(check);
    check_octree_levels(check, "voxels");
    check_lpv_buffer(check, LpvBuffer::Levels, "levels", "voxels");
    check_lpv_buffer(check, LpvBuffer::Radiance, "radiance", "voxels");
  };
  registry.add(std::move(info), [] { return std::make_unique<MergePass>(); });
}

}  // namespace voxgi::passes::lpv
