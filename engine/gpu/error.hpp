#pragma once
// Errors of the gpu layer. Every failure throws gpu::Error with a message that says what
// failed, the VkResult name when there is one, and what to do about it.

#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace voxgi::gpu {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// The enum name of a VkResult ("VK_ERROR_OUT_OF_DEVICE_MEMORY"), or "VkResult(<n>)".
const char* to_string(VkResult result);

// Throws Error("<what> failed: <VkResult name>[: hint]") unless result is VK_SUCCESS
// (or another non-negative status code such as VK_INCOMPLETE).
void check(VkResult result, const char* what);

}  // namespace voxgi::gpu
