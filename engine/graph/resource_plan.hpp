#pragma once
// The resource half of compilation, run on an ordered graph: usage flags, lifetimes, shared
// physical resources, memory estimates, and the layouts and barriers between passes. FrameSync
// also plans the barriers of each frame at run time, when some passes skip it.

#include <utility>
#include <vector>

#include "engine/graph/compiler.hpp"

namespace voxgi::graph {

void plan_resources(CompiledGraph& graph, const CompileOptions& options);

// Bytes of one resource: texel size x extent over all mips x layers, or the buffer size.
uint64_t estimate_bytes(const ResourceInfo& info);

// Usage flags a slot's access needs.
VkImageUsageFlags image_usage_for(Access access);
VkBufferUsageFlags buffer_usage_for(Access access);

// The barriers of one frame, in recording order.
struct FrameBarriers {
  std::vector<Barrier> frame_start;
  std::vector<std::vector<Barrier>> passes;  // recorded before each scheduled pass
  std::vector<Barrier> history;              // before the previous-frame copies
  std::vector<Barrier> frame_end;
};

// Same kind, format, extent, mips, layers, clipmap levels and buffer size (names and
// persistence aside): what can live in the same allocation.
bool same_description(const ResourceInfo& a, const ResourceInfo& b);

// Vulkan barriers (image, buffer and global memory barriers) in a frame.
size_t barrier_count(const FrameBarriers& frame);

// What the barriers so far guarantee for one mip of one physical resource.
struct SyncTrack {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 write_stages = 0;  // last write (or layout transition)
  VkAccessFlags2 write_access = 0;
  VkPipelineStageFlags2 read_stages = 0;                                  // reads since then
  std::vector<std::pair<VkPipelineStageFlags2, VkAccessFlags2>> visible;  // where it is visible
};

// Plans the barriers of consecutive frames from what the frames before left. A pass that
// skips a frame gets no barriers, and neither does what it would have written: a later reader
// gets one only where the resource was written this frame or is in another layout. Every frame
// ends with each resource in the layout a frame of all passes ends in (its end_state), so that
// rebuilds and read-backs find it there.
class FrameSync {
 public:
  // Starts as every frame after the first does when all passes run. The graph needs its
  // physical resources planned and must outlive this object.
  explicit FrameSync(const CompiledGraph& graph);

  // The next frame's barriers; skipped[s] is true for a scheduled pass that skips it.
  FrameBarriers plan(const std::vector<bool>& skipped);

  // The barriers of a frame in which every pass runs, as every frame after the first has them.
  const FrameBarriers& all_passes_frame() const { return all_passes_frame_; }
  // What one mip of a physical resource is known to be in now.
  ResourceState state(size_t physical, uint32_t mip) const;

 private:
  const CompiledGraph* graph_;
  std::vector<std::vector<SyncTrack>> tracks_;  // per physical resource and mip
  // Per memory block: the allocation using it now and what it has done there, which the next
  // one to move in must wait for (its first barrier then carries those stages and writes).
  std::vector<int> block_owner_;
  std::vector<SyncTrack> block_use_;
  // Per physical resource and mip: the last use in a frame of all passes (the layout every
  // frame ends in), and in the frame just planned.
  std::vector<std::vector<ResourceState>> end_use_;
  std::vector<std::vector<ResourceState>> last_use_;
  FrameBarriers all_passes_frame_;
};

}  // namespace voxgi::graph
