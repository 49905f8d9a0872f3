#include <algorithm>
#include <string>

#include "engine/gpu/error.hpp"
#include "engine/gpu/image.hpp"

namespace voxgi::gpu {

namespace {

struct FormatInfo {
  VkFormat format;
  uint32_t bytes;
  const char* name;
};

constexpr FormatInfo kFormats[] = {
    {VK_FORMAT_R8_UNORM, 1, "VK_FORMAT_R8_UNORM"},
    {VK_FORMAT_R8G8_UNORM, 2, "VK_FORMAT_R8G8_UNORM"},
    {VK_FORMAT_R8G8B8A8_UNORM, 4, "VK_FORMAT_R8G8B8A8_UNORM"},
    {VK_FORMAT_R8G8B8A8_SRGB, 4, "VK_FORMAT_R8G8B8A8_SRGB"},
    {VK_FORMAT_B8G8R8A8_UNORM, 4, "VK_FORMAT_B8G8R8A8_UNORM"},
    {VK_FORMAT_B8G8R8A8_SRGB, 4, "VK_FORMAT_B8G8R8A8_SRGB"},
    {VK_FORMAT_R8G8B8A8_UINT, 4, "VK_FORMAT_R8G8B8A8_UINT"},
    {VK_FORMAT_R16_SFLOAT, 2, "VK_FORMAT_R16_SFLOAT"},
    {VK_FORMAT_R16G16_SFLOAT, 4, "VK_FORMAT_R16G16_SFLOAT"},
    {VK_FORMAT_R16G16B16A16_SFLOAT, 8, "VK_FORMAT_R16G16B16A16_SFLOAT"},
    {VK_FORMAT_R16G16B16A16_UNORM, 8, "VK_FORMAT_R16G16B16A16_UNORM"},
    {VK_FORMAT_R32_SFLOAT, 4, "VK_FORMAT_R32_SFLOAT"},
    {VK_FORMAT_R32G32_SFLOAT, 8, "VK_FORMAT_R32G32_SFLOAT"},
    {VK_FORMAT_R32G32B32A32_SFLOAT, 16, "VK_FORMAT_R32G32B32A32_SFLOAT"},
    {VK_FORMAT_R32_UINT, 4, "VK_FORMAT_R32_UINT"},
    {VK_FORMAT_R32_SINT, 4, "VK_FORMAT_R32_SINT"},
    {VK_FORMAT_R32G32_UINT, 8, "VK_FORMAT_R32G32_UINT"},
    {VK_FORMAT_R32G32B32A32_UINT, 16, "VK_FORMAT_R32G32B32A32_UINT"},
    {VK_FORMAT_B10G11R11_UFLOAT_PACK32, 4, "VK_FORMAT_B10G11R11_UFLOAT_PACK32"},
    {VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4, "VK_FORMAT_A2B10G10R10_UNORM_PACK32"},
    {VK_FORMAT_D32_SFLOAT, 4, "VK_FORMAT_D32_SFLOAT"},
    {VK_FORMAT_D16_UNORM, 2, "VK_FORMAT_D16_UNORM"},
};

const FormatInfo* find_format(VkFormat format) {
  for (const auto& info : kFormats) {
    if (info.format == format) return &info;
  }
  return nullptr;
}

}  // namespace

uint32_t full_mip_count(VkExtent3D extent) {
  uint32_t largest = std::max({extent.width, extent.height, extent.depth, 1u});
  uint32_t count = 1;
  while (largest > 1) {
    largest >>= 1;
    ++count;
  }
  return count;
}

VkExtent3D mip_extent(VkExtent3D extent, uint32_t mip) {
  return {std::max(1u, extent.width >> mip), std::max(1u, extent.height >> mip),
          std::max(1u, extent.depth >> mip)};
}

bool is_depth_format(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return true;
    default:
      return false;
  }
}

VkImageAspectFlags aspect_of(VkFormat format) {
  return is_depth_format(format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
}

uint32_t bytes_per_texel(VkFormat format) {
  if (const FormatInfo* info = find_format(format)) return info->bytes;
  throw Error("bytes_per_texel: format " + std::to_string(static_cast<int>(format)) +
              " is not one voxgi uses; expected one of the formats listed in "
              "engine/gpu/image.hpp");
}

const char* format_name(VkFormat format) {
  if (const FormatInfo* info = find_format(format)) return info->name;
  if (format == VK_FORMAT_UNDEFINED) return "VK_FORMAT_UNDEFINED";
  return "VkFormat(other)";
}

}  // namespace voxgi::gpu
