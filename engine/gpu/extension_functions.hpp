#pragma once
// Internal to engine/gpu: device-extension entry points the loader does not export.
// Loaded through vkGetInstanceProcAddr, whose trampolines dispatch on the command buffer, so
// one pointer serves every device of the process.

#include <vulkan/vulkan.h>

namespace voxgi::gpu {

void load_extension_functions(VkInstance instance);
// Throws Error when no context has loaded it yet.
PFN_vkCmdPushDescriptorSetKHR push_descriptor_set_function();

}  // namespace voxgi::gpu
