// lpv.propagate: decodes the injection, builds the geometry volume and runs the iterations of
// the 6-neighbour x 5-face propagation, accumulating every iteration (shaders/lpv/propagate.comp
// derives the transfer). Skips when the injection, the voxels and its parameters did not
// change.

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

struct PropagatePush {
  uint32_t mode;
  uint32_t src;
  float factor;
  uint32_t pad;
};

constexpr uint32_t kLocal = 4;

class PropagatePass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    occlusion_ = ctx.flag("occlusion");
    const bool directional = ctx.choice("reprojection") == "directional";
    std::vector<gpu::Binding> bindings = {{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                          {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                          {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0},
                                          {3, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 0}};
    if (occlusion_) {
      bindings.push_back({4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
      bindings.push_back({5, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 0});
    }
    pipeline_.emplace(
        graph::make_pass_compute(ctx, "lpv/propagate.comp", bindings, sizeof(PropagatePush), false,
                                 {{"HAS_OCCLUSION", occlusion_ ? "1" : "0"},
                                  {"REPROJECT_DIRECTIONAL", directional ? "1" : "0"}}));
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
        .storage_buffer(2, *ctx.resource("work").buffer)
        .storage_buffer(3, *ctx.resource("radiance").buffer);
    if (occlusion_) {
      const graph::BoundResource& normal = ctx.resource("normal");
      writer.sampled_image(4, albedo.view, albedo.layout, nearest)
          .sampled_image(5, normal.view, normal.layout, nearest);
    }
    pipeline_->bind(cmd);
    writer.push(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    const VkExtent3D e = albedo.info->extent;
    PropagatePush push{0, 0, static_cast<float>(ctx.number("factor")), 0};
    const auto dispatch = [&]() {
      pipeline_->push_constants(cmd, push);
      vkCmdDispatch(cmd, groups(e.width, kLocal), groups(e.height, kLocal),
                    groups(e.depth, kLocal));
      ctx.barrier_within_pass("work");
      ctx.barrier_within_pass("radiance");
    };
    dispatch();
    push.mode = 1;
    const int iterations = static_cast<int>(ctx.integer("iterations"));
    for (int i = 0; i < iterations; ++i) {
      push.src = static_cast<uint32_t>(i % 2);
      dispatch();
    }
    // What the last iteration's light reaches.
    push.mode = 2;
    push.src = static_cast<uint32_t>(iterations % 2);
    dispatch();
    versions_.remember(ctx);
  }

 private:
  bool occlusion_ = false;
  std::optional<gpu::ComputePipeline> pipeline_;
  graph::InputVersions versions_{{"clipmap_info", "injected", "albedo", "normal"}};
};

}  // namespace

void register_propagate(graph::Registry& registry) {
  graph::PassTypeInfo info;
  info.type = "lpv.propagate";
  info.doc =
      "LPV propagation: 6 neighbours x 5 faces with exact face integrals, optional "
      "geometry-volume occlusion from the voxels, every iteration accumulated";
  info.inputs = {
      contracts::clipmap_info_input(),
      {"injected",
       graph::kinds(graph::ResourceKind::Buffer),
       graph::Access::StorageRead,
       graph::kStageCompute,
       {},
       false,
       "lpv.inject's fixed-point intensities"},
      graph::sampled_clipmap_input(
          "albedo", "voxel opacity (a): the LPV has one cell per voxel of this clipmap", false,
          {contracts::kVoxelAlbedoFormat, VK_FORMAT_R16G16B16A16_SFLOAT}),
      graph::sampled_clipmap_input("normal", "voxel normals, for the blocking potential", false,
                                   {contracts::kVoxelNormalFormat, VK_FORMAT_R32G32B32A32_SFLOAT}),
  };
  info.outputs = {
      {"radiance",
       graph::kinds(graph::ResourceKind::Buffer),
       graph::Access::StorageWrite,
       graph::kStageCompute,
       {},
       false,
       "per cell: accumulated SH intensity, the flux its geometry stopped, its geometry "
       "(lpv/cells.glsl)"},
      {"work",
       graph::kinds(graph::ResourceKind::Buffer),
       graph::Access::StorageWrite,
       graph::kStageCompute,
       {},
       false,
       "two propagation states and the geometry volume",
       true},
  };
  info.params = {
      {"iterations",
       graph::ParamType::Int,
       64.0,
       0.0,
       1024.0,
       {},
       "propagation steps (one cell each); light reaches this many cells from its source",
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
      {"occlusion",
       graph::ParamType::Bool,
       1.0,
       0.0,
       1.0,
       {},
       "block propagation by the voxels' geometry volume",
       false},
  };
  graph::set_size_rule(info, "radiance", lpv_buffer_size(LpvBuffer::Radiance, "albedo"));
  graph::set_size_rule(info, "work", lpv_buffer_size(LpvBuffer::Work, "albedo"));
  info.may_skip = true;
  info.validate = [](graph::PassCheck& check) {
    contracts::check_clipmap_info_size(check);
    graph::check_same_clipmap_layout(check, "albedo", {"normal"});
    check_lpv_buffer(check, LpvBuffer::Injected, "injected", "albedo");
    check_lpv_buffer(check, LpvBuffer::Radiance, "radiance", "albedo");
    check_lpv_buffer(check, LpvBuffer::Work, "work", "albedo");
  };
  registry.add(std::move(info), [] { return std::make_unique<PropagatePass>(); });
}

}  // namespace voxgi::passes::lpv
