#pragma once
// Device memory allocation behind an interface, so a sub-allocator can replace the
// dedicated one without touching buffers and images.

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>

namespace voxgi::gpu {

enum class MemoryUsage {
  GpuOnly,   // device local, not mapped
  CpuToGpu,  // host visible (coherent preferred), persistently mapped; uploads, uniforms
  GpuToCpu,  // host visible, cached preferred, persistently mapped; read-backs
};

struct Allocation {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // non-null for host-visible usages
  bool coherent = true;    // false: the owner must flush / invalidate mapped ranges
};

class Allocator {
 public:
  virtual ~Allocator();
  // Throws Error when no memory type fits or the device is out of memory.
  virtual Allocation allocate(const VkMemoryRequirements& requirements, MemoryUsage usage) = 0;
  virtual void free(const Allocation& allocation) = 0;
  virtual VkDeviceSize bytes_in_use() const = 0;
};

// One VkDeviceMemory per allocation. Simple and correct; fine for the handful of large
// resources a frame graph allocates.
class DedicatedAllocator final : public Allocator {
 public:
  DedicatedAllocator(VkPhysicalDevice physical_device, VkDevice device);
  Allocation allocate(const VkMemoryRequirements& requirements, MemoryUsage usage) override;
  void free(const Allocation& allocation) override;
  VkDeviceSize bytes_in_use() const override { return bytes_in_use_.load(); }

  // Index of the best memory type for usage among type_bits, or UINT32_MAX.
  uint32_t find_memory_type(uint32_t type_bits, MemoryUsage usage) const;

 private:
  VkDevice device_;
  VkPhysicalDeviceMemoryProperties properties_{};
  std::atomic<VkDeviceSize> bytes_in_use_{0};
};

// Device memory that several resources bind to one after another (their lifetimes within a
// frame do not overlap: the frame graph's aliasing of transients). It must outlive every
// resource bound to it; those do not free it.
class SharedMemory {
 public:
  // `requirements`: the largest size and alignment of the resources, the memory types all of
  // them accept. Throws Error like Allocator::allocate.
  SharedMemory(Allocator& allocator, const VkMemoryRequirements& requirements);
  ~SharedMemory();
  SharedMemory(const SharedMemory&) = delete;
  SharedMemory& operator=(const SharedMemory&) = delete;

  const Allocation& allocation() const { return allocation_; }

 private:
  Allocator& allocator_;
  Allocation allocation_;
};

// Tag for constructors that create a resource without memory: bind_memory() binds it later.
struct BindLater {};

}  // namespace voxgi::gpu
