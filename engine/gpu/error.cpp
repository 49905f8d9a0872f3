#include "engine/gpu/error.hpp"

#include <string>
#include <string_view>

namespace voxgi::gpu {

const char* to_string(VkResult result) {
  switch (result) {
#define VOXGI_RESULT(name) \
  case name:               \
    return #name;
    VOXGI_RESULT(VK_SUCCESS)
    VOXGI_RESULT(VK_NOT_READY)
    VOXGI_RESULT(VK_TIMEOUT)
    VOXGI_RESULT(VK_EVENT_SET)
    VOXGI_RESULT(VK_EVENT_RESET)
    VOXGI_RESULT(VK_INCOMPLETE)
    VOXGI_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    VOXGI_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    VOXGI_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    VOXGI_RESULT(VK_ERROR_DEVICE_LOST)
    VOXGI_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    VOXGI_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    VOXGI_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    VOXGI_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    VOXGI_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    VOXGI_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    VOXGI_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    VOXGI_RESULT(VK_ERROR_FRAGMENTED_POOL)
    VOXGI_RESULT(VK_ERROR_UNKNOWN)
    VOXGI_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
    VOXGI_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    VOXGI_RESULT(VK_ERROR_FRAGMENTATION)
    VOXGI_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    VOXGI_RESULT(VK_PIPELINE_COMPILE_REQUIRED)
    VOXGI_RESULT(VK_ERROR_SURFACE_LOST_KHR)
    VOXGI_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    VOXGI_RESULT(VK_SUBOPTIMAL_KHR)
    VOXGI_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
    VOXGI_RESULT(VK_ERROR_INCOMPATIBLE_DISPLAY_KHR)
    VOXGI_RESULT(VK_ERROR_VALIDATION_FAILED_EXT)
    VOXGI_RESULT(VK_ERROR_INVALID_SHADER_NV)
#undef VOXGI_RESULT
    default:
      return "VkResult(unknown)";
  }
}

namespace {

// What a user can do about the common failures.
const char* hint_for(VkResult result) {
  switch (result) {
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      return "reduce resolutions or volume sizes, or close other GPU applications";
    case VK_ERROR_DEVICE_LOST:
      return "the GPU driver reset the device; run with --validation to find the cause";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "no Vulkan 1.3 driver found: install mesa-vulkan-drivers (lavapipe) or a GPU "
             "driver";
    case VK_ERROR_LAYER_NOT_PRESENT:
      return "install vulkan-validationlayers";
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_FEATURE_NOT_PRESENT:
      return "the device or driver lacks a required capability; try another --device or "
             "update the driver";
    default:
      return nullptr;
  }
}

}  // namespace

void check(VkResult result, const char* what) {
  if (result >= 0) return;
  std::string message(what);
  message.append(" failed: ").append(to_string(result));
  if (std::string_view(to_string(result)) == "VkResult(unknown)") {
    message.append(" (").append(std::to_string(static_cast<int>(result))).append(")");
  }
  if (const char* hint = hint_for(result)) message.append(": ").append(hint);
  throw Error(message);
}

}  // namespace voxgi::gpu
