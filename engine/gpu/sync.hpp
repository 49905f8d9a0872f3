#pragma once
// Small synchronization2 helpers for tools, tests and transfers outside the render graph.

#include <vulkan/vulkan.h>

namespace voxgi::gpu {

// A global memory barrier.
void memory_barrier(VkCommandBuffer cmd, VkPipelineStageFlags2 src_stages,
                    VkAccessFlags2 src_access, VkPipelineStageFlags2 dst_stages,
                    VkAccessFlags2 dst_access);
// Stages and accesses on one side of a barrier.
struct BarrierScope {
  VkPipelineStageFlags2 stages;
  VkAccessFlags2 access;
};
// One image layout transition (or, with from == to, a plain dependency) on `range`.
void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range,
                   VkImageLayout from, VkImageLayout to, BarrierScope src, BarrierScope dst);
// Everything before (all writes) is done and visible to everything after. Heavy; for
// one-shot work such as uploads and read-backs.
void full_barrier(VkCommandBuffer cmd);

}  // namespace voxgi::gpu
