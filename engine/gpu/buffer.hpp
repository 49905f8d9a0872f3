#pragma once
// A VkBuffer with its memory. Host-visible buffers are persistently mapped; GPU-only ones
// go through a staging buffer for upload and download.

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "engine/gpu/memory.hpp"

namespace voxgi::gpu {

class Context;

class Buffer {
 public:
  // GpuOnly buffers get TRANSFER_DST and TRANSFER_SRC added to usage so upload() and
  // download() work. size must be > 0.
  Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
         std::string name);
  // A GpuOnly buffer without memory: bind_memory() binds memory the caller owns (SharedMemory).
  Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, std::string name,
         BindLater);
  ~Buffer();
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return allocation_.mapped; }  // null for GpuOnly
  MemoryUsage memory_usage() const { return memory_; }
  const std::string& name() const { return name_; }
  VkMemoryRequirements memory_requirements() const;
  // Once, for a buffer made with BindLater; the memory stays the caller's.
  void bind_memory(const Allocation& memory);

  // memcpy when mapped, else a staging copy with immediate_submit (waits for the queue).
  // Throws Error when [offset, offset + size) is outside the buffer.
  void upload(const void* data, VkDeviceSize size, VkDeviceSize offset = 0);
  void download(void* dst, VkDeviceSize size, VkDeviceSize offset = 0);

  template <typename T>
  void upload_vector(const std::vector<T>& values, VkDeviceSize offset = 0) {
    upload(values.data(), values.size() * sizeof(T), offset);
  }
  // The whole buffer (or count elements from offset) as T.
  template <typename T>
  std::vector<T> download_vector(size_t count = 0, VkDeviceSize offset = 0) {
    if (count == 0) count = static_cast<size_t>((size_ - offset) / sizeof(T));
    std::vector<T> values(count);
    download(values.data(), count * sizeof(T), offset);
    return values;
  }

 private:
  void create(VkBufferUsageFlags usage);
  void destroy();
  void check_range(VkDeviceSize size, VkDeviceSize offset, const char* what) const;

  Context* context_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  Allocation allocation_{};
  bool owns_memory_ = true;
  VkDeviceSize size_ = 0;
  MemoryUsage memory_ = MemoryUsage::GpuOnly;
  std::string name_;
};

}  // namespace voxgi::gpu
