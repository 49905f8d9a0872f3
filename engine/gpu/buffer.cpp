#include "engine/gpu/buffer.hpp"

#include <cstring>
#include <utility>

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"
#include "engine/gpu/sync.hpp"

namespace voxgi::gpu {

Buffer::Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUsage memory,
               std::string name)
    : context_(&context), size_(size), memory_(memory), name_(std::move(name)) {
  create(usage);
  try {
    allocation_ = context.allocator().allocate(memory_requirements(), memory);
    check(vkBindBufferMemory(context.device(), buffer_, allocation_.memory, allocation_.offset),
          "vkBindBufferMemory");
  } catch (const Error& error) {
    destroy();
    throw Error("buffer \"" + name_ + "\" (" + std::to_string(size) + " bytes): " + error.what());
  }
}

Buffer::Buffer(Context& context, VkDeviceSize size, VkBufferUsageFlags usage, std::string name,
               BindLater)
    : context_(&context),
      owns_memory_(false),
      size_(size),
      memory_(MemoryUsage::GpuOnly),
      name_(std::move(name)) {
  create(usage);
}

void Buffer::create(VkBufferUsageFlags usage) {
  if (size_ == 0) throw Error("buffer \"" + name_ + "\": size must be greater than 0");
  if (memory_ == MemoryUsage::GpuOnly) {
    usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
  }
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size_;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(context_->device(), &info, nullptr, &buffer_),
        ("vkCreateBuffer for \"" + name_ + "\"").c_str());
  context_->set_debug_name(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<uint64_t>(buffer_), name_);
}

VkMemoryRequirements Buffer::memory_requirements() const {
  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(context_->device(), buffer_, &requirements);
  return requirements;
}

void Buffer::bind_memory(const Allocation& memory) {
  check(vkBindBufferMemory(context_->device(), buffer_, memory.memory, memory.offset),
        ("vkBindBufferMemory for buffer \"" + name_ + "\"").c_str());
  allocation_ = memory;
  owns_memory_ = false;
}

Buffer::~Buffer() {
  destroy();
}

Buffer::Buffer(Buffer&& other) noexcept
    : context_(other.context_),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      allocation_(std::exchange(other.allocation_, Allocation{})),
      owns_memory_(other.owns_memory_),
      size_(std::exchange(other.size_, 0)),
      memory_(other.memory_),
      name_(std::move(other.name_)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    destroy();
    context_ = other.context_;
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    allocation_ = std::exchange(other.allocation_, Allocation{});
    owns_memory_ = other.owns_memory_;
    size_ = std::exchange(other.size_, 0);
    memory_ = other.memory_;
    name_ = std::move(other.name_);
  }
  return *this;
}

void Buffer::destroy() {
  if (!context_) return;
  if (buffer_) vkDestroyBuffer(context_->device(), buffer_, nullptr);
  if (allocation_.memory && owns_memory_) context_->allocator().free(allocation_);
  buffer_ = VK_NULL_HANDLE;
  allocation_ = Allocation{};
}

void Buffer::check_range(VkDeviceSize size, VkDeviceSize offset, const char* what) const {
  if (offset > size_ || size > size_ - offset) {
    throw Error(std::string(what) + " of buffer \"" + name_ + "\": range [" +
                std::to_string(offset) + ", " + std::to_string(offset + size) +
                ") is outside its " + std::to_string(size_) + " bytes");
  }
}

void Buffer::upload(const void* data, VkDeviceSize size, VkDeviceSize offset) {
  check_range(size, offset, "upload");
  if (size == 0) return;
  if (allocation_.mapped) {
    std::memcpy(static_cast<char*>(allocation_.mapped) + offset, data, size);
    if (!allocation_.coherent) {
      VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
      range.memory = allocation_.memory;
      range.size = VK_WHOLE_SIZE;
      check(vkFlushMappedMemoryRanges(context_->device(), 1, &range), "vkFlushMappedMemoryRanges");
    }
    return;
  }
  Buffer staging(*context_, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::CpuToGpu,
                 name_ + ".staging");
  staging.upload(data, size);
  context_->immediate_submit([&](VkCommandBuffer cmd) {
    // Earlier GPU work on this buffer (other submissions) must not race the copy.
    full_barrier(cmd);
    VkBufferCopy copy{0, offset, size};
    vkCmdCopyBuffer(cmd, staging.handle(), buffer_, 1, &copy);
    full_barrier(cmd);
  });
}

void Buffer::download(void* dst, VkDeviceSize size, VkDeviceSize offset) {
  check_range(size, offset, "download");
  if (size == 0) return;
  if (allocation_.mapped) {
    if (!allocation_.coherent) {
      VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE};
      range.memory = allocation_.memory;
      range.size = VK_WHOLE_SIZE;
      check(vkInvalidateMappedMemoryRanges(context_->device(), 1, &range),
            "vkInvalidateMappedMemoryRanges");
    }
    std::memcpy(dst, static_cast<const char*>(allocation_.mapped) + offset, size);
    return;
  }
  Buffer staging(*context_, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::GpuToCpu,
                 name_ + ".staging");
  context_->immediate_submit([&](VkCommandBuffer cmd) {
    full_barrier(cmd);
    VkBufferCopy copy{offset, 0, size};
    vkCmdCopyBuffer(cmd, buffer_, staging.handle(), 1, &copy);
    memory_barrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  });
  staging.download(dst, size);
}

}  // namespace voxgi::gpu
