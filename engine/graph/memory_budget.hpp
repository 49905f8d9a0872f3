#pragma once
// The device memory a compiled graph needs, checked against what the device has before any of
// it is allocated: a graph whose sizes exceed it (a 256^3 x 6-level clipmap on a small GPU)
// gets a message naming the largest resources and the budget, instead of an allocation
// failure or, on a CPU device, the system's out-of-memory killer.

#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include "engine/graph/compiler.hpp"

namespace voxgi::graph {

// Bytes the graph may allocate on this device: the largest device-local memory heap of a GPU
// (VK_EXT_memory_budget would be tighter; the heap size is the hard limit), the system's
// available memory for a CPU device. 0: unknown (no check).
uint64_t device_memory_budget(VkPhysicalDevice device);

// Throws GraphError, located at the largest resource, when graph.total_bytes exceeds `budget`.
void check_memory_budget(const CompiledGraph& graph, uint64_t budget);

}  // namespace voxgi::graph
