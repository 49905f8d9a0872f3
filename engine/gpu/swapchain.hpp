#pragma once
// A swapchain for a window surface on the context's queue. The surface comes from the window
// system (e.g. glfwCreateWindowSurface) and stays the caller's; the context must have been
// created with the surface's instance extensions and VK_KHR_swapchain.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace voxgi::gpu {

class Context;

// True when the context's queue family can present to `surface`.
bool queue_supports_present(Context& context, VkSurfaceKHR surface);

class Swapchain {
 public:
  // Throws Error when the queue cannot present to the surface or the surface offers no
  // 8-bit UNORM colour format. Images are COLOR_ATTACHMENT and TRANSFER_DST (and TRANSFER_SRC
  // where the surface allows).
  Swapchain(Context& context, VkSurfaceKHR surface, VkExtent2D wanted);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // After a resize or an out-of-date result; waits for the queue first.
  void recreate(VkExtent2D wanted);

  // The index of the next image, signalling `acquired` when it may be written; nullopt when
  // the swapchain is out of date (recreate it).
  std::optional<uint32_t> acquire(VkSemaphore acquired);
  // False when the swapchain is out of date or suboptimal (recreate it).
  bool present(uint32_t index, VkSemaphore wait);

  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  uint32_t image_count() const { return static_cast<uint32_t>(images_.size()); }
  uint32_t min_image_count() const { return min_image_count_; }
  VkImage image(uint32_t i) const { return images_[i]; }
  VkImageView view(uint32_t i) const { return views_[i]; }
  // True when the images can be copied from (TRANSFER_SRC), e.g. to capture the window.
  bool readable() const { return can_read_; }
  // True when the format stores blue first (B8G8R8A8): callers writing texels swap R and B.
  bool bgr_order() const;

 private:
  void create(VkExtent2D wanted, VkSwapchainKHR old);
  void destroy_views();

  Context& context_;
  VkSurfaceKHR surface_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR color_space_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkExtent2D extent_{0, 0};
  uint32_t min_image_count_ = 2;
  bool can_read_ = false;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
};

}  // namespace voxgi::gpu
