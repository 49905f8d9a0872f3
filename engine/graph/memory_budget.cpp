#include "engine/graph/memory_budget.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <vector>

#include "engine/graph/diagnostics.hpp"

namespace voxgi::graph {

namespace {

std::string gib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f GiB", static_cast<double>(bytes) / double(1ull << 30));
  return text;
}

}  // namespace

// MemAvailable of /proc/meminfo (what can be allocated without swapping), else 0.
static uint64_t available_system_memory() {
  std::ifstream meminfo("/proc/meminfo");
  std::string key;
  uint64_t kib = 0;
  std::string unit;
  while (meminfo >> key >> kib >> unit) {
    if (key == "MemAvailable:") return kib * 1024;
  }
  return 0;
}

uint64_t device_memory_budget(VkPhysicalDevice device) {
  VkPhysicalDeviceProperties device_properties{};
  vkGetPhysicalDeviceProperties(device, &device_properties);
  // A CPU device (lavapipe) allocates system memory whatever heap size it reports (2 GiB for
  // lavapipe, which runs far larger graphs): its limit is the memory the system has free.
  if (device_properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) {
    return available_system_memory();
  }
  VkPhysicalDeviceMemoryProperties properties{};
  vkGetPhysicalDeviceMemoryProperties(device, &properties);
  uint64_t largest = 0;
  for (uint32_t i = 0; i < properties.memoryHeapCount; ++i) {
    if (properties.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) {
      largest = std::max<uint64_t>(largest, properties.memoryHeaps[i].size);
    }
  }
  return largest;
}

void check_memory_budget(const CompiledGraph& graph, uint64_t budget) {
  if (budget == 0 || graph.total_bytes <= budget) return;
  std::vector<const CompiledResource*> live;
  for (const CompiledResource& r : graph.resources) {
    if (r.physical >= 0) live.push_back(&r);
  }
  std::sort(live.begin(), live.end(), [](const CompiledResource* a, const CompiledResource* b) {
    return a->bytes > b->bytes;
  });
  std::string largest;
  for (size_t i = 0; i < live.size() && i < 4; ++i) {
    largest += (i ? ", " : "") + live[i]->info.name + " " + gib(live[i]->bytes);
  }
  Diagnostic diagnostic;
  diagnostic.loc = live.empty() ? SourceLoc{graph.file, 0, 0} : live.front()->loc;
  diagnostic.field = live.empty() ? std::string() : "resources." + live.front()->info.name;
  diagnostic.message = "the graph needs " + gib(graph.total_bytes) +
                       " of device memory, more than the device's " + gib(budget) +
                       " (largest: " + largest +
                       "); lower the resource sizes (the graph's parameters, --set)";
  throw GraphError(diagnostic);
}

}  // namespace voxgi::graph
