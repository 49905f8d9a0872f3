// A pass family that exists only for tests: it uses the mechanisms no shipped family uses yet,
// so that they stay tested on the baseline device. "example.trace_args" traces rays through
// the scene's BVH service and writes indirect dispatch arguments; "example.mark" reads them as
// an indirect access and dispatches that many groups. tests/example/example.json chooses the
// tracing pass by a device feature.
#include <memory>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/pass.hpp"
#include "engine/scene/gpu_bvh.hpp"

namespace {

using namespace voxgi;
using graph::Access;
using graph::ResourceKind;

std::unique_ptr<gpu::ComputePipeline> compute_pipeline(graph::PassContext& ctx, const char* shader,
                                                       uint32_t buffers, uint32_t push_size) {
  gpu::PipelineLayoutDesc layout;
  for (uint32_t b = 0; b < buffers; ++b) {
    layout.bindings.push_back({b, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, VK_SHADER_STAGE_COMPUTE_BIT});
  }
  layout.push_constant_size = push_size;
  layout.push_constant_stages = push_size > 0 ? VK_SHADER_STAGE_COMPUTE_BIT : 0;
  return std::make_unique<gpu::ComputePipeline>(ctx.gpu(), ctx.shaders().compile({shader}), layout,
                                                ctx.pass_name());
}

class TraceArgsPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    ctx.scene_bvh();
    pipeline_ = compute_pipeline(ctx, "example/trace_args.comp", 6, sizeof(uint32_t));
  }
  void execute(graph::PassContext& ctx) override {
    const scene::GpuBvh& bvh = ctx.scene_bvh();
    pipeline_->bind(ctx.cmd());
    gpu::DescriptorWriter()
        .storage_buffer(0, *ctx.resource("args").buffer)
        .storage_buffer(1, *ctx.resource("marks").buffer)
        .storage_buffer(2, bvh.nodes())
        .storage_buffer(3, bvh.triangles())
        .storage_buffer(4, bvh.shading())
        .storage_buffer(5, bvh.emitters())
        .push(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    pipeline_->push_constants(ctx.cmd(), bvh.node_count());
    vkCmdDispatch(ctx.cmd(), 1, 1, 1);
  }

 private:
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
};

class MarkPass final : public graph::Pass {
 public:
  void setup(graph::PassContext& ctx) override {
    pipeline_ = compute_pipeline(ctx, "example/mark.comp", 1, 0);
  }
  void execute(graph::PassContext& ctx) override {
    pipeline_->bind(ctx.cmd());
    gpu::DescriptorWriter()
        .storage_buffer(0, *ctx.resource("marks").buffer)
        .push(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_->layout());
    vkCmdDispatchIndirect(ctx.cmd(), ctx.resource("args").buffer->handle(), 0);
  }

 private:
  std::unique_ptr<gpu::ComputePipeline> pipeline_;
};

graph::SlotSpec buffer_slot(const char* name, Access access, const char* doc) {
  graph::SlotSpec slot;
  slot.name = name;
  slot.kinds = graph::kinds(ResourceKind::Buffer);
  slot.access = access;
  slot.stages = graph::kStageCompute;
  slot.doc = doc;
  return slot;
}

// Both buffers hold at least what the shaders index.
void check_sizes(graph::PassCheck& check) {
  if (check.has("args") && check.info("args").buffer_size < 16) {
    check.slot_error("args", "needs at least 16 bytes (uvec4)");
  }
  if (check.has("marks") && check.info("marks").buffer_size < 64 * sizeof(uint32_t)) {
    check.slot_error("marks", "needs at least 256 bytes (64 marks)");
  }
}

}  // namespace

VOXGI_PLUGIN_EXPORT uint32_t voxgi_plugin_abi_version() {
  return voxgi::graph::kPluginAbiVersion;
}

VOXGI_PLUGIN_EXPORT void voxgi_plugin_register(voxgi::graph::Registry& registry) {
  using namespace voxgi::graph;
  PassTypeInfo trace;
  trace.type = "example.trace_args";
  trace.doc = "64 rays down through the scene's BVH; the hits become indirect dispatch arguments";
  trace.outputs = {
      buffer_slot("args", Access::StorageWrite, "vkCmdDispatchIndirect arguments (hits, 1, 1)"),
      buffer_slot("marks", Access::StorageWrite, "64 marks, cleared")};
  trace.validate = check_sizes;
  registry.add(trace, [] { return std::make_unique<TraceArgsPass>(); });

  PassTypeInfo mark;
  mark.type = "example.mark";
  mark.doc = "one group per hit, dispatched indirectly; group g sets mark g to g + 1";
  mark.inputs = {buffer_slot("args", Access::IndirectRead, "dispatch arguments")};
  mark.outputs = {buffer_slot("marks", Access::StorageReadWrite, "the marks")};
  mark.validate = check_sizes;
  registry.add(mark, [] { return std::make_unique<MarkPass>(); });
}
