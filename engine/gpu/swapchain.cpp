#include "engine/gpu/swapchain.hpp"

#include <algorithm>

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"

namespace voxgi::gpu {

bool queue_supports_present(Context& context, VkSurfaceKHR surface) {
  VkBool32 supported = VK_FALSE;
  check(vkGetPhysicalDeviceSurfaceSupportKHR(context.physical_device(), context.queue_family(),
                                             surface, &supported),
        "vkGetPhysicalDeviceSurfaceSupportKHR");
  return supported == VK_TRUE;
}

Swapchain::Swapchain(Context& context, VkSurfaceKHR surface, VkExtent2D wanted)
    : context_(context), surface_(surface) {
  if (!queue_supports_present(context_, surface_)) {
    throw Error("the queue of " + context_.device_name() +
                " cannot present to this window: choose another --device");
  }
  uint32_t count = 0;
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(context_.physical_device(), surface_, &count, nullptr),
        "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(count);
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(context_.physical_device(), surface_, &count,
                                             formats.data()),
        "vkGetPhysicalDeviceSurfaceFormatsKHR");
  // UNORM, not SRGB: what is written has been display-encoded already (OCIO).
  for (VkFormat wanted_format : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM}) {
    for (const VkSurfaceFormatKHR& f : formats) {
      if (f.format == wanted_format && format_ == VK_FORMAT_UNDEFINED) {
        format_ = f.format;
        color_space_ = f.colorSpace;
      }
    }
  }
  if (format_ == VK_FORMAT_UNDEFINED) {
    throw Error("the window surface offers no B8G8R8A8_UNORM or R8G8B8A8_UNORM format");
  }
  create(wanted, VK_NULL_HANDLE);
}

Swapchain::~Swapchain() {
  context_.wait_idle();
  destroy_views();
  if (swapchain_) vkDestroySwapchainKHR(context_.device(), swapchain_, nullptr);
}

bool Swapchain::bgr_order() const {
  return format_ == VK_FORMAT_B8G8R8A8_UNORM;
}

void Swapchain::destroy_views() {
  for (VkImageView view : views_) vkDestroyImageView(context_.device(), view, nullptr);
  views_.clear();
  images_.clear();
}

void Swapchain::recreate(VkExtent2D wanted) {
  context_.wait_idle();
  destroy_views();
  VkSwapchainKHR old = swapchain_;
  swapchain_ = VK_NULL_HANDLE;
  try {
    create(wanted, old);
  } catch (...) {
    vkDestroySwapchainKHR(context_.device(), old, nullptr);
    throw;
  }
  vkDestroySwapchainKHR(context_.device(), old, nullptr);
}

void Swapchain::create(VkExtent2D wanted, VkSwapchainKHR old) {
  VkSurfaceCapabilitiesKHR caps{};
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_.physical_device(), surface_, &caps),
        "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  if (caps.currentExtent.width != UINT32_MAX) {
    extent_ = caps.currentExtent;
  } else {
    extent_.width = std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height =
        std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  extent_.width = std::max(extent_.width, 1u);
  extent_.height = std::max(extent_.height, 1u);
  min_image_count_ = std::max(2u, caps.minImageCount);
  uint32_t image_count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) image_count = std::min(image_count, caps.maxImageCount);
  image_count = std::max(image_count, min_image_count_);

  // FIFO is always there; MAILBOX keeps latency low where offered.
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;
  uint32_t mode_count = 0;
  vkGetPhysicalDeviceSurfacePresentModesKHR(context_.physical_device(), surface_, &mode_count,
                                            nullptr);
  std::vector<VkPresentModeKHR> modes(mode_count);
  vkGetPhysicalDeviceSurfacePresentModesKHR(context_.physical_device(), surface_, &mode_count,
                                            modes.data());
  if (std::find(modes.begin(), modes.end(), VK_PRESENT_MODE_MAILBOX_KHR) != modes.end()) {
    mode = VK_PRESENT_MODE_MAILBOX_KHR;
  }

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = image_count;
  info.imageFormat = format_;
  info.imageColorSpace = color_space_;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  // Readable where the surface allows it, for window captures.
  can_read_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
  if (can_read_) info.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
  info.presentMode = mode;
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  check(vkCreateSwapchainKHR(context_.device(), &info, nullptr, &swapchain_),
        "vkCreateSwapchainKHR");

  uint32_t count = 0;
  vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, nullptr);
  images_.resize(count);
  vkGetSwapchainImagesKHR(context_.device(), swapchain_, &count, images_.data());
  for (VkImage image : images_) {
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format_;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView handle = VK_NULL_HANDLE;
    check(vkCreateImageView(context_.device(), &view, nullptr, &handle), "vkCreateImageView");
    views_.push_back(handle);
  }
}

std::optional<uint32_t> Swapchain::acquire(VkSemaphore acquired) {
  uint32_t index = 0;
  const VkResult result = vkAcquireNextImageKHR(context_.device(), swapchain_, UINT64_MAX, acquired,
                                                VK_NULL_HANDLE, &index);
  if (result == VK_ERROR_OUT_OF_DATE_KHR) return std::nullopt;
  if (result != VK_SUBOPTIMAL_KHR) check(result, "vkAcquireNextImageKHR");
  return index;
}

bool Swapchain::present(uint32_t index, VkSemaphore wait) {
  VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &wait;
  info.swapchainCount = 1;
  info.pSwapchains = &swapchain_;
  info.pImageIndices = &index;
  const VkResult result = vkQueuePresentKHR(context_.queue(), &info);
  if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) return false;
  check(result, "vkQueuePresentKHR");
  return true;
}

}  // namespace voxgi::gpu
