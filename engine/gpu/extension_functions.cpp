#include "engine/gpu/extension_functions.hpp"

#include <atomic>

#include "engine/gpu/error.hpp"

namespace voxgi::gpu {

namespace {
std::atomic<PFN_vkCmdPushDescriptorSetKHR> push_descriptor_set{nullptr};
}  // namespace

void load_extension_functions(VkInstance instance) {
  auto function = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetInstanceProcAddr(instance, "vkCmdPushDescriptorSetKHR"));
  if (!function) {
    throw Error(
        "the Vulkan loader has no vkCmdPushDescriptorSetKHR: update libvulkan1 and the driver");
  }
  push_descriptor_set.store(function);
}

PFN_vkCmdPushDescriptorSetKHR push_descriptor_set_function() {
  PFN_vkCmdPushDescriptorSetKHR function = push_descriptor_set.load();
  if (!function) throw Error("push descriptors used before any gpu::Context was created");
  return function;
}

}  // namespace voxgi::gpu
