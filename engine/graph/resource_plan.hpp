#pragma once
// The resource half of compilation, run on an ordered graph: usage flags, lifetimes, shared
// physical resources, memory estimates, and the layouts and barriers between passes.

#include "engine/graph/compiler.hpp"

namespace voxgi::graph {

void plan_resources(CompiledGraph& graph, const CompileOptions& options);

// Bytes of one resource: texel size x extent over all mips x layers, or the buffer size.
uint64_t estimate_bytes(const ResourceInfo& info);

// Usage flags a slot's access needs.
VkImageUsageFlags image_usage_for(Access access);
VkBufferUsageFlags buffer_usage_for(Access access);

}  // namespace voxgi::graph
