#include "engine/graph/pass_helpers.hpp"

#include "engine/gpu/context.hpp"
#include "engine/gpu/image.hpp"
#include "engine/scene/gpu_scene.hpp"

namespace voxgi::graph {

SlotSpec sampled_2d_input(const char* name, const char* doc, bool optional,
                          std::vector<VkFormat> formats) {
  return {name,
          kinds(ResourceKind::Image2D),
          Access::Sampled,
          kStageCompute,
          std::move(formats),
          optional,
          doc};
}

SlotSpec sampled_clipmap_input(const char* name, const char* doc, bool optional,
                               std::vector<VkFormat> formats) {
  return {name,
          kinds(ResourceKind::Clipmap),
          Access::Sampled,
          kStageCompute,
          std::move(formats),
          optional,
          doc};
}

SlotSpec compute_buffer_slot(const char* name, Access access, const char* doc, bool scratch) {
  SlotSpec slot;
  slot.name = name;
  slot.kinds = kinds(ResourceKind::Buffer);
  slot.access = access;
  slot.stages = kStageCompute;
  slot.doc = doc;
  slot.scratch = scratch;
  return slot;
}

std::vector<uint32_t> compile_pass_shader(const PassContext& ctx, const std::string& path,
                                          std::vector<gpu::ShaderDefine> defines) {
  gpu::ShaderRequest request;
  request.path = path;
  request.defines = std::move(defines);
  return ctx.shaders().compile(request);
}

gpu::ComputePipeline make_pass_compute(const PassContext& ctx, const std::string& path,
                                       std::vector<gpu::Binding> bindings,
                                       uint32_t push_constant_size, bool with_scene_set,
                                       std::vector<gpu::ShaderDefine> defines) {
  gpu::PipelineLayoutDesc layout;
  layout.bindings = std::move(bindings);
  for (gpu::Binding& binding : layout.bindings) binding.stages = VK_SHADER_STAGE_COMPUTE_BIT;
  if (with_scene_set) layout.extra_set_layouts = {ctx.gpu_scene().set_layout()};
  layout.push_constant_size = push_constant_size;
  layout.push_constant_stages = VK_SHADER_STAGE_COMPUTE_BIT;
  return gpu::ComputePipeline(ctx.gpu(), compile_pass_shader(ctx, path, std::move(defines)), layout,
                              ctx.pass_name());
}

VkExtent3D bound_extent(const ResourceInfo& info) {
  return info.mip > 0 ? gpu::mip_extent(info.extent, static_cast<uint32_t>(info.mip)) : info.extent;
}

void check_same_clipmap_layout(PassCheck& check, std::string_view reference,
                               std::initializer_list<const char*> slots) {
  if (!check.has(reference)) return;
  const ResourceInfo& want = check.info(reference);
  auto text = [](const ResourceInfo& info) {
    const VkExtent3D e = bound_extent(info);
    return std::to_string(e.width) + "x" + std::to_string(e.height) + "x" +
           std::to_string(e.depth) + " in " + std::to_string(info.clipmap_levels) + " level(s)";
  };
  for (const char* slot : slots) {
    if (!check.has(slot)) continue;
    const ResourceInfo& info = check.info(slot);
    const VkExtent3D a = bound_extent(info);
    const VkExtent3D b = bound_extent(want);
    if (a.width == b.width && a.height == b.height && a.depth == b.depth &&
        info.clipmap_levels == want.clipmap_levels) {
      continue;
    }
    check.slot_error(slot, "volume '" + info.name + "' is " + text(info) + ", but '" +
                               std::string(reference) + "' ('" + want.name + "') is " + text(want) +
                               "; voxel volumes are addressed texel for texel, so "
                               "both need the same resolution and levels");
  }
}

void bind_scene_set(const PassContext& ctx, const gpu::ComputePipeline& pipeline) {
  VkDescriptorSet set = ctx.gpu_scene().descriptor_set();
  vkCmdBindDescriptorSets(ctx.cmd(), VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 1, 1, &set,
                          0, nullptr);
}

std::vector<uint64_t> InputVersions::current(const PassContext& ctx) const {
  std::vector<uint64_t> versions;
  versions.reserve(slots_.size());
  // resource_version() wants a bound slot.
  for (const std::string& slot : slots_) {
    versions.push_back(ctx.has(slot) ? ctx.resource_version(slot) : 0);
  }
  return versions;
}

bool InputVersions::changed(const PassContext& ctx) const {
  return !valid_ || seen_ != current(ctx);
}

void InputVersions::remember(const PassContext& ctx) {
  seen_ = current(ctx);
  valid_ = true;
}

}  // namespace voxgi::graph
