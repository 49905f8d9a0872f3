#pragma once
// GPU timestamps in a query pool, for per-pass timings.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

namespace voxgi::gpu {

class Context;

class TimestampQueries {
 public:
  static constexpr uint32_t kInvalid = UINT32_MAX;

  // No pool is created when the device has no timestamps; write() then returns kInvalid.
  TimestampQueries(Context& context, uint32_t max_queries);
  ~TimestampQueries();
  TimestampQueries(const TimestampQueries&) = delete;
  TimestampQueries& operator=(const TimestampQueries&) = delete;

  bool supported() const { return pool_ != VK_NULL_HANDLE; }
  uint32_t capacity() const { return max_queries_; }
  uint32_t count() const { return used_; }

  // Resets every query (recorded in cmd, before any write()) and the write counter.
  void reset(VkCommandBuffer cmd);
  // Writes a timestamp after `stage`; returns its index, or kInvalid when full/unsupported.
  uint32_t write(VkCommandBuffer cmd, VkPipelineStageFlags2 stage);
  // The raw values of the written queries (masked to timestampValidBits), after the
  // submission that wrote them completed. Throws Error if not available.
  std::vector<uint64_t> read();
  // Time between two raw values, in milliseconds (timestampPeriod respected, wrap handled).
  double milliseconds(uint64_t begin, uint64_t end) const;

 private:
  Context* context_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t max_queries_ = 0;
  uint32_t used_ = 0;
  uint64_t valid_mask_ = ~0ull;
  double period_ns_ = 1.0;
};

}  // namespace voxgi::gpu
