#include "engine/gpu/device_selection.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "engine/gpu/error.hpp"

namespace voxgi::gpu {

namespace {

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// Discrete beats integrated beats virtual beats CPU (lavapipe is the fallback).
int type_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 1;
    default:
      return 0;
  }
}

std::string unsuitable_reason(const PhysicalDeviceInfo& info) {
  if (info.properties.apiVersion < VK_API_VERSION_1_3) return "Vulkan 1.3 not supported";
  if (info.queue_family == UINT32_MAX) return "no graphics+compute queue";
  if (!has_device_extension(info.handle, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) {
    return "VK_KHR_push_descriptor missing";
  }
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  f12.pNext = &f13;
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f.pNext = &f12;
  vkGetPhysicalDeviceFeatures2(info.handle, &f);
  if (!f13.dynamicRendering) return "dynamicRendering missing";
  if (!f13.synchronization2) return "synchronization2 missing";
  if (!f12.scalarBlockLayout) return "scalarBlockLayout missing";
  if (!f.features.fragmentStoresAndAtomics) return "fragmentStoresAndAtomics missing";
  if (!f.features.shaderStorageImageWriteWithoutFormat) {
    return "shaderStorageImageWriteWithoutFormat missing";
  }
  return "";
}

}  // namespace

const char* device_type_name(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

bool has_device_extension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  for (const auto& extension : extensions) {
    if (std::strcmp(extension.extensionName, name) == 0) return true;
  }
  return false;
}

std::vector<PhysicalDeviceInfo> describe_devices(VkInstance instance) {
  uint32_t count = 0;
  check(vkEnumeratePhysicalDevices(instance, &count, nullptr), "vkEnumeratePhysicalDevices");
  std::vector<VkPhysicalDevice> handles(count);
  check(vkEnumeratePhysicalDevices(instance, &count, handles.data()), "vkEnumeratePhysicalDevices");
  std::vector<PhysicalDeviceInfo> devices;
  for (uint32_t i = 0; i < count; ++i) {
    PhysicalDeviceInfo info;
    info.handle = handles[i];
    info.index = i;
    vkGetPhysicalDeviceProperties(info.handle, &info.properties);
    if (info.properties.apiVersion >= VK_API_VERSION_1_2) {
      VkPhysicalDeviceVulkan12Properties p12{
          VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
      VkPhysicalDeviceProperties2 p{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
      p.pNext = &p12;
      vkGetPhysicalDeviceProperties2(info.handle, &p);
      info.driver = p12.driverName;
      if (p12.driverInfo[0] != '\0') info.driver += std::string(" ") + p12.driverInfo;
    } else {
      info.driver = "driver " + std::to_string(info.properties.driverVersion);
    }
    uint32_t family_count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(info.handle, &family_count, nullptr);
    std::vector<VkQueueFamilyProperties> families(family_count);
    vkGetPhysicalDeviceQueueFamilyProperties(info.handle, &family_count, families.data());
    for (uint32_t f = 0; f < family_count; ++f) {
      VkQueueFlags need = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
      if ((families[f].queueFlags & need) == need) {
        info.queue_family = f;
        break;
      }
    }
    info.unsuitable = unsuitable_reason(info);
    devices.push_back(std::move(info));
  }
  return devices;
}

std::string describe(const PhysicalDeviceInfo& info) {
  uint32_t v = info.properties.apiVersion;
  std::string text = std::to_string(info.index) + ": " + info.properties.deviceName + " (" +
                     device_type_name(info.properties.deviceType) + ", " + info.driver + ", API " +
                     std::to_string(VK_API_VERSION_MAJOR(v)) + "." +
                     std::to_string(VK_API_VERSION_MINOR(v)) + "." +
                     std::to_string(VK_API_VERSION_PATCH(v)) + ")";
  if (!info.unsuitable.empty()) text += " [unusable: " + info.unsuitable + "]";
  return text;
}

namespace {

std::string device_list(const std::vector<PhysicalDeviceInfo>& devices) {
  std::string text;
  for (const auto& info : devices) text += "\n  " + describe(info);
  return text;
}

}  // namespace

const PhysicalDeviceInfo& choose_device(const std::vector<PhysicalDeviceInfo>& devices,
                                        const std::string& selector) {
  if (devices.empty()) {
    throw Error("no Vulkan device found: install mesa-vulkan-drivers (lavapipe) or a GPU driver");
  }
  if (!selector.empty()) {
    bool is_index = std::all_of(selector.begin(), selector.end(),
                                [](unsigned char c) { return std::isdigit(c) != 0; });
    const PhysicalDeviceInfo* match = nullptr;
    for (const auto& info : devices) {
      bool hit = is_index
                     ? std::to_string(info.index) == selector
                     : lower(info.properties.deviceName).find(lower(selector)) != std::string::npos;
      if (hit) {
        match = &info;
        break;
      }
    }
    if (!match) {
      throw Error("no Vulkan device matches --device \"" + selector +
                  "\" (expected an index or part of a device name); available devices:" +
                  device_list(devices));
    }
    if (!match->unsuitable.empty()) {
      throw Error("Vulkan device \"" + std::string(match->properties.deviceName) +
                  "\" cannot be used: " + match->unsuitable +
                  "; choose another with --device; available devices:" + device_list(devices));
    }
    return *match;
  }
  const PhysicalDeviceInfo* best = nullptr;
  for (const auto& info : devices) {
    if (!info.unsuitable.empty()) continue;
    if (!best || type_rank(info.properties.deviceType) > type_rank(best->properties.deviceType)) {
      best = &info;
    }
  }
  if (!best) {
    throw Error(
        "no Vulkan device is suitable (voxgi needs Vulkan 1.3 with dynamic rendering, "
        "synchronization2 and VK_KHR_push_descriptor): update the driver or install "
        "mesa-vulkan-drivers (lavapipe); devices:" +
        device_list(devices));
  }
  return *best;
}

}  // namespace voxgi::gpu
