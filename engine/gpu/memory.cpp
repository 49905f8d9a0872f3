#include "engine/gpu/memory.hpp"

#include <string>

#include "engine/gpu/error.hpp"

namespace voxgi::gpu {

Allocator::~Allocator() = default;

DedicatedAllocator::DedicatedAllocator(VkPhysicalDevice physical_device, VkDevice device)
    : device_(device) {
  vkGetPhysicalDeviceMemoryProperties(physical_device, &properties_);
}

uint32_t DedicatedAllocator::find_memory_type(uint32_t type_bits, MemoryUsage usage) const {
  VkMemoryPropertyFlags required = 0;
  VkMemoryPropertyFlags preferred = 0;
  switch (usage) {
    case MemoryUsage::GpuOnly:
      preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUsage::CpuToGpu:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
    case MemoryUsage::GpuToCpu:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_COHERENT_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  // Best match: all required bits, then the most preferred bits; ties go to the lower index
  // (drivers order types by preference).
  uint32_t best = UINT32_MAX;
  int best_score = -1;
  for (uint32_t i = 0; i < properties_.memoryTypeCount; ++i) {
    if (!(type_bits & (1u << i))) continue;
    VkMemoryPropertyFlags flags = properties_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    int score = __builtin_popcount(flags & preferred);
    if (score > best_score) {
      best = i;
      best_score = score;
    }
  }
  return best;
}

Allocation DedicatedAllocator::allocate(const VkMemoryRequirements& requirements,
                                        MemoryUsage usage) {
  uint32_t type = find_memory_type(requirements.memoryTypeBits, usage);
  if (type == UINT32_MAX) {
    throw Error("no Vulkan memory type fits (type bits 0x" +
                std::to_string(requirements.memoryTypeBits) + ", " +
                (usage == MemoryUsage::GpuOnly ? "GpuOnly" : "host visible") +
                "): the driver exposes no suitable memory; try another --device");
  }
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = requirements.size;
  info.memoryTypeIndex = type;
  Allocation allocation;
  VkResult result = vkAllocateMemory(device_, &info, nullptr, &allocation.memory);
  if (result != VK_SUCCESS) {
    check(result, ("vkAllocateMemory of " + std::to_string(requirements.size) + " bytes").c_str());
  }
  allocation.size = requirements.size;
  VkMemoryPropertyFlags flags = properties_.memoryTypes[type].propertyFlags;
  allocation.coherent = (flags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT) != 0;
  if (usage != MemoryUsage::GpuOnly) {
    result = vkMapMemory(device_, allocation.memory, 0, VK_WHOLE_SIZE, 0, &allocation.mapped);
    if (result != VK_SUCCESS) {
      vkFreeMemory(device_, allocation.memory, nullptr);
      check(result, "vkMapMemory");
    }
  }
  bytes_in_use_ += allocation.size;
  return allocation;
}

void DedicatedAllocator::free(const Allocation& allocation) {
  if (allocation.memory == VK_NULL_HANDLE) return;
  // Freeing implicitly unmaps.
  vkFreeMemory(device_, allocation.memory, nullptr);
  bytes_in_use_ -= allocation.size;
}

SharedMemory::SharedMemory(Allocator& allocator, const VkMemoryRequirements& requirements)
    : allocator_(allocator), allocation_(allocator.allocate(requirements, MemoryUsage::GpuOnly)) {}

SharedMemory::~SharedMemory() {
  allocator_.free(allocation_);
}

}  // namespace voxgi::gpu
