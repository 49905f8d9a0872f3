#include "engine/gpu/timestamps.hpp"

#include <vector>

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"

namespace voxgi::gpu {

TimestampQueries::TimestampQueries(Context& context, uint32_t max_queries)
    : context_(&context), max_queries_(max_queries) {
  if (!context.features().timestamps || max_queries == 0) return;
  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(context.physical_device(), &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(context.physical_device(), &family_count,
                                           families.data());
  uint32_t bits = families[context.queue_family()].timestampValidBits;
  valid_mask_ = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
  period_ns_ = context.features().timestamp_period_ns;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = max_queries;
  check(vkCreateQueryPool(context.device(), &info, nullptr, &pool_), "vkCreateQueryPool");
}

TimestampQueries::~TimestampQueries() {
  if (pool_) vkDestroyQueryPool(context_->device(), pool_, nullptr);
}

void TimestampQueries::reset(VkCommandBuffer cmd) {
  used_ = 0;
  if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, max_queries_);
}

uint32_t TimestampQueries::write(VkCommandBuffer cmd, VkPipelineStageFlags2 stage) {
  if (!pool_ || used_ >= max_queries_) return kInvalid;
  vkCmdWriteTimestamp2(cmd, stage, pool_, used_);
  return used_++;
}

std::vector<uint64_t> TimestampQueries::read() {
  std::vector<uint64_t> values(used_);
  if (!pool_ || used_ == 0) return values;
  VkResult result =
      vkGetQueryPoolResults(context_->device(), pool_, 0, used_, values.size() * sizeof(uint64_t),
                            values.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
  if (result == VK_NOT_READY) {
    throw Error(
        "timestamp queries read before the submission that wrote them completed; wait for its "
        "fence first");
  }
  check(result, "vkGetQueryPoolResults");
  for (uint64_t& value : values) value &= valid_mask_;
  return values;
}

double TimestampQueries::milliseconds(uint64_t begin, uint64_t end) const {
  // Counters wrap at timestampValidBits.
  uint64_t ticks = (end - begin) & valid_mask_;
  return double(ticks) * period_ns_ * 1e-6;
}

}  // namespace voxgi::gpu
