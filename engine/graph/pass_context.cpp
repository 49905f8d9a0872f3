// PassDeclaration and PassCheck over a compiled pass; PassContext over the executor's
// PassContextImpl.
#include <algorithm>
#include <stdexcept>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/image.hpp"
#include "engine/graph/pass_context_impl.hpp"
#include "engine/scene/gpu_scene.hpp"

namespace voxgi::graph {

size_t PassContextImpl::binding_index(std::string_view slot) const {
  for (size_t i = 0; i < pass->bindings.size(); ++i) {
    if (pass->bindings[i].slot == slot) return i;
  }
  throw std::invalid_argument("pass '" + pass->name + "' (" + pass->type + ") has no bound slot '" +
                              std::string(slot) + "'");
}

const std::string& PassDeclaration::pass_name() const {
  return pass_.name;
}

bool PassDeclaration::has(std::string_view slot) const {
  const SlotBinding* b = pass_.binding(slot);
  return b && b->resource >= 0;
}

const ResourceInfo& PassDeclaration::info(std::string_view slot) const {
  const SlotBinding* b = pass_.binding(slot);
  if (!b) {
    throw std::invalid_argument("pass '" + pass_.name + "' (" + pass_.type +
                                ") has no bound slot '" + std::string(slot) + "'");
  }
  if (b->resource < 0) {
    throw std::invalid_argument("pass '" + pass_.name + "': optional slot '" + std::string(slot) +
                                "' is unbound (check has() first)");
  }
  return b->info;
}

double PassDeclaration::number(std::string_view param) const {
  auto it = pass_.params.find(std::string(param));
  if (it == pass_.params.end()) {
    throw std::invalid_argument("pass '" + pass_.name + "' (" + pass_.type +
                                ") has no parameter '" + std::string(param) + "'");
  }
  return it->second.number;
}

const std::string& PassDeclaration::choice(std::string_view param) const {
  number(param);  // checks that it exists
  return pass_.params.at(std::string(param)).text;
}

void PassCheck::param_error(std::string_view param, std::string message) {
  number(param);  // checks that it exists
  report_("params." + std::string(param), std::move(message));
}

void PassCheck::slot_error(std::string_view slot, std::string message) {
  const SlotBinding* b = pass_.binding(slot);
  bool is_input = b && b->is_input;
  if (!b && pass_.type_info) {
    for (const SlotSpec& s : pass_.type_info->inputs) is_input = is_input || s.name == slot;
  }
  report_((is_input ? "in." : "out.") + std::string(slot), std::move(message));
}

PassContext::PassContext(PassContextImpl& impl) : PassDeclaration(*impl.pass), impl_(impl) {}

gpu::Context& PassContext::gpu() const {
  return *impl_.gpu;
}
gpu::ShaderCompiler& PassContext::shaders() const {
  return *impl_.shaders;
}
const scene::Scene& PassContext::scene() const {
  return *impl_.scene;
}
scene::GpuScene& PassContext::gpu_scene() const {
  return *impl_.gpu_scene;
}

const scene::GpuBvh& PassContext::scene_bvh() const {
  return impl_.gpu_scene->bvh(*impl_.scene);
}
const FrameInfo& PassContext::frame() const {
  return *impl_.frame;
}

uint64_t PassContext::resource_version(std::string_view slot) const {
  const SlotBinding* b = impl_.pass->binding(slot);
  if (!b) {
    const PassTypeInfo* type = impl_.pass->type_info;
    if (type) {
      for (const auto* slots : {&type->inputs, &type->outputs}) {
        for (const SlotSpec& s : *slots) {
          if (s.name == slot) return 0;  // an optional slot left unbound
        }
      }
    }
    throw std::invalid_argument("pass '" + impl_.pass->name + "': no slot '" + std::string(slot) +
                                "'");
  }
  if (b->resource < 0 || !impl_.resource_versions) return 0;
  return (*impl_.resource_versions)[static_cast<size_t>(b->resource)];
}

const BoundResource& PassContext::resource(std::string_view slot) const {
  if (!impl_.executing) {
    throw std::logic_error("pass '" + impl_.pass->name + "': resource('" + std::string(slot) +
                           "') is only available during execute()");
  }
  info(slot);  // checks that the slot exists and is bound
  return impl_.bound[impl_.binding_index(slot)];
}

bool PassContext::params_changed() const {
  return impl_.params_changed;
}

VkCommandBuffer PassContext::cmd() const {
  if (!impl_.executing) {
    throw std::logic_error("pass '" + impl_.pass->name +
                           "': cmd() is only available during execute()");
  }
  return impl_.cmd;
}

void PassContext::barrier_within_pass(std::string_view slot, int src_mip, int dst_mip) const {
  const BoundResource& r = resource(slot);
  const SlotBinding& b = impl_.pass->bindings[impl_.binding_index(slot)];
  // The slot's own stages plus compute, where mip chains and multi-dispatch passes run.
  const VkPipelineStageFlags2 stages = b.state.stages | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  const VkAccessFlags2 access = VK_ACCESS_2_SHADER_READ_BIT | VK_ACCESS_2_SHADER_WRITE_BIT;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  VkImageMemoryBarrier2 image{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  VkBufferMemoryBarrier2 buffer{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
  if (r.buffer) {
    buffer.srcStageMask = buffer.dstStageMask = stages;
    buffer.srcAccessMask = buffer.dstAccessMask = access;
    buffer.srcQueueFamilyIndex = buffer.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    buffer.buffer = r.buffer->handle();
    buffer.size = VK_WHOLE_SIZE;
    dependency.bufferMemoryBarrierCount = 1;
    dependency.pBufferMemoryBarriers = &buffer;
  } else {
    // Default: the mips the slot is bound to; else the span between the two mips given.
    uint32_t first = b.info.mip < 0 ? 0 : static_cast<uint32_t>(b.info.mip);
    uint32_t count = b.info.mip < 0 ? b.info.mip_levels : 1;
    if (src_mip >= 0 || dst_mip >= 0) {
      const int lo = std::min(src_mip < 0 ? dst_mip : src_mip, dst_mip < 0 ? src_mip : dst_mip);
      const int hi = std::max(src_mip, dst_mip);
      if (hi >= static_cast<int>(b.info.mip_levels)) {
        throw std::invalid_argument("pass '" + impl_.pass->name + "': barrier_within_pass('" +
                                    std::string(slot) + "') mip " + std::to_string(hi) +
                                    " is outside the resource's " +
                                    std::to_string(b.info.mip_levels) + " mips");
      }
      first = static_cast<uint32_t>(lo);
      count = static_cast<uint32_t>(hi - lo + 1);
    }
    image.srcStageMask = image.dstStageMask = stages;
    image.srcAccessMask = image.dstAccessMask = access;
    image.oldLayout = image.newLayout = r.layout;
    image.srcQueueFamilyIndex = image.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    image.image = r.image->handle();
    image.subresourceRange = {r.image->aspect(), first, count, 0, b.info.array_layers};
    dependency.imageMemoryBarrierCount = 1;
    dependency.pImageMemoryBarriers = &image;
  }
  vkCmdPipelineBarrier2(impl_.cmd, &dependency);
}

}  // namespace voxgi::graph
