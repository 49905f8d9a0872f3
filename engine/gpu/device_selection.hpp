#pragma once
// Internal to engine/gpu: describing physical devices and choosing one.

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

namespace voxgi::gpu {

struct PhysicalDeviceInfo {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  uint32_t index = 0;
  VkPhysicalDeviceProperties properties{};
  std::string driver;
  uint32_t queue_family = UINT32_MAX;  // first graphics+compute family
  std::string unsuitable;              // why it cannot be used; "" when suitable
};

std::vector<PhysicalDeviceInfo> describe_devices(VkInstance instance);
// "index: name (type, driver, API x.y.z)".
std::string describe(const PhysicalDeviceInfo& info);
const char* device_type_name(VkPhysicalDeviceType type);
// selector: "" = best suitable device by type, else an index or a case-insensitive name
// substring. Throws Error listing the devices when nothing fits.
const PhysicalDeviceInfo& choose_device(const std::vector<PhysicalDeviceInfo>& devices,
                                        const std::string& selector);
bool has_device_extension(VkPhysicalDevice device, const char* name);

}  // namespace voxgi::gpu
