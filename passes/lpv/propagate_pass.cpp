// lpv.propagate: the 6-neighbour x 5-face propagation on every octree level, each with its own
// number of steps, accumulating them (shaders/lpv/propagate.comp derives the transfer). Skips
// when the injected levels and its parameters did not change.

#include <algorithm>
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

struct PropagatePush {
  uint32_t mode;
  uint32_t src;
  uint32_t step;
  int32_t cell_begin;
  float factor;
  uint32_t shell_start;
  uint32_t octree_levels;
  int32_t cell_total;
  uint32_t iterations[kMaxOctreeLevels];
};

constexpr uint32_t kLocal = 64;

// The steps of each octree level. Level 0 takes the user's k. A coarser level of n cells per
// side stops once light can have crossed it (3 (n - 1) steps along the 6-neighbour paths; the
// seed's n - 1 counts an axis only). With the shells merge the last level runs until then
// whatever k is: it holds every distance the finer levels do not.
std::vector<uint32_t> level_iterations(uint32_t resolution, uint32_t octree_levels, uint32_t k,
                                       bool shells) {
  std::vector<uint32_t> steps(octree_levels, k);
  for (uint32_t o = 1; o < octree_levels; ++o) {
    const uint32_t crossing = 3 * ((resolution >> o) - 1);
    steps[o] = shells && o + 1 == octree_levels ? crossing : std::min(k, crossing);
  }
  return steps;
}

class PropagatePass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    const bool directional = ctx.choice("reprojection") == "directional";
    pipeline_.emplace(graph::make_pass_compute(
        ctx, "lpv/propagate.comp",
        {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
         {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
         {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
         {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0}},
        sizeof(PropagatePush), false, {{"REPROJECT_DIRECTIONAL", directional ? "1" : "0"}}));
    versions_.forget();
  }

  std::string skip_reason(const graph::PassContext& ctx) const override {
    if (ctx.params_changed()) return {};
    return !versions_.changed(ctx) ? "injected levels unchanged" : std::string();
  }

  void execute(graph::PassContext& ctx) override {
    VkCommandBuffer cmd = ctx.cmd();
    gpu::DescriptorWriter writer;
    writer.storage_buffer(0, *ctx.resource("clipmap_info").buffer)
        .storage_buffer(1, *ctx.resource("injected_levels").buffer)
        .storage_buffer(2, *ctx.resource("work").buffer)
        .storage_buffer(3, *ctx.resource("levels").buffer);
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());

    const graph::ResourceInfo& clipmap = *ctx.resource("voxels").info;
    const auto octree_levels = static_cast<uint32_t>(ctx.integer("octree_levels"));
    const auto k = static_cast<uint32_t>(ctx.integer("iterations"));
    const bool shells = ctx.choice("merge") == "shells";
    const std::vector<uint32_t> steps =
        level_iterations(clipmap.extent.width, octree_levels, k, shells);
    // The first cell of each level; level o's cells are [begin[o], begin[o + 1]).
    std::vector<uint64_t> begin(octree_levels + 1);
    for (uint32_t o = 0; o <= octree_levels; ++o) begin[o] = lpv_octree_cell_count(clipmap, o);

    PropagatePush push{};
    push.factor = static_cast<float>(ctx.number("factor"));
    push.shell_start = shells && octree_levels > 1 ? k / 2 + 1 : 0;
    push.octree_levels = octree_levels;
    push.cell_total = static_cast<int32_t>(begin[octree_levels]);
    for (uint32_t o = 0; o < octree_levels; ++o) push.iterations[o] = steps[o];
    const auto dispatch = [&](uint64_t first, uint64_t end) {
      push.cell_begin = static_cast<int32_t>(first);
      pipeline_->push_constants(cmd, push);
      vkCmdDispatch(cmd, graph::workgroups(end - first, kLocal), 1, 1);
    };
    dispatch(0, begin[octree_levels]);
    const uint32_t last_step = *std::max_element(steps.begin(), steps.end());
    push.mode = 1;
    for (uint32_t t = 0; t <= last_step; ++t) {
      ctx.barrier_within_pass("work");
      ctx.barrier_within_pass("levels");
      push.step = t;
      push.src = t % 2;
      // One dispatch per run of consecutive levels that still step (at their last step they
      // only count what their geometry stops).
      for (uint32_t o = 0; o < octree_levels;) {
        if (steps[o] < t) {
          ++o;
          continue;
        }
        uint32_t end = o;
        while (end < octree_levels && steps[end] >= t) ++end;
        dispatch(begin[o], begin[end]);
        o = end;
      }
    }
    versions_.remember(ctx);
  }

 private:
  std::optional<gpu::ComputePipeline> pipeline_;
  graph::InputVersions versions_{{"clipmap_info", "injected_levels", "voxels"}};
};

}  // namespace

void register_propagate(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "lpv.propagate";
  info.doc =
      "LPV propagation on every octree level (seed 002's LPVPropagate): 6 neighbours x 5 faces "
      "with exact face integrals, blocked by lpv.downsample's geometry volume, every step "
      "accumulated";
  info.inputs = {
      contracts::clipmap_info_input(),
      graph::compute_buffer_slot("injected_levels", graph::Access::StorageRead,
                                 "lpv.downsample's injected levels and geometry volume"),
      graph::sampled_clipmap_input("voxels",
                                   "the clipmap whose voxels are the LPV's cells (its layout)"),
  };
  info.outputs = {
      graph::compute_buffer_slot(
          "levels", graph::Access::StorageWrite,
          "per cell of every octree level: accumulated SH intensity, the flux its geometry "
          "stopped and the index mark, its geometry (lpv/cells.glsl)"),
      graph::compute_buffer_slot("work", graph::Access::StorageWrite,
                                 "two propagation states per cell of every octree level", true),
  };
  info.params = {
      {"iterations",
       graph::ParamType::Int,
       64.0,
       0.0,
       1024.0,
       {},
       "propagation steps (one cell each) of octree level 0; light reaches this many cells "
       "from its source. Coarser levels take the same, up to what crosses them",
       true},
      {"factor",
       graph::ParamType::Float,
       1.0,
       0.0,
       16.0,
       {},
       "propagation factor p: 1 carries the flux unchanged; seed 002 uses 3, which hides its "
       "missing 1/pi and resolution scale",
       true},
      {"reprojection",
       graph::ParamType::Enum,
       0.0,
       0.0,
       0.0,
       {"directional", "cosine"},
       "how a cell re-emits the flux a face received: directional keeps the direction it "
       "crossed the face in (its flux and first moment); cosine is seed 002's lobe along the "
       "face's normal, which turns light 90 degrees at every side face and makes the transport "
       "diffuse (docs/lpv.md)",
       false},
      octree_levels_param(),
      merge_param(),
  };
  graph::set_size_rule(info, "levels", lpv_buffer_size(LpvBuffer::Levels, "voxels"));
  graph::set_size_rule(info, "work", lpv_buffer_size(LpvBuffer::Work, "voxels"));
  info.may_skip = true;
  info.validate = [](graph::PassCheck& check) {
    contracts::check_clipmap_info_size(check);
    check_octree_levels(check, "voxels");
    check_lpv_buffer(check, LpvBuffer::Levels, "injected_levels", "voxels");
    check_lpv_buffer(check, LpvBuffer::Levels, "levels", "voxels");
    check_lpv_buffer(check, LpvBuffer::Work, "work", "voxels");
  };
  registry.add(std::move(info), [] { return std::make_unique<PropagatePass>(); });
}

}  // namespace voxgi::passes::lpv
