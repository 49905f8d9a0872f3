#pragma once
// Puts the viewer's image and its Dear ImGui panel on the window: a surface and swapchain,
// a render pass for the UI, one frame in flight. The image (the graph's output, composed on
// the CPU) is copied into the swapchain image at the top-left; the UI is drawn over the rest.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/swapchain.hpp"

struct GLFWwindow;
struct ImDrawData;

namespace voxgi::gpu {
class Context;
}

namespace voxgi::viewer {

class Presenter {
 public:
  // Creates the surface for `window` and initialises ImGui's Vulkan backend (ImGui's context
  // and GLFW backend must exist). Throws gpu::Error with the reason.
  Presenter(gpu::Context& context, GLFWwindow* window);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // True when texels must be given as BGRA (the swapchain's byte order).
  bool bgr() const { return swapchain_->bgr_order(); }

  // Copies `bytes` (width × height texels, 4 bytes each) to the window's top-left, draws `ui`
  // over it and presents. Recreates the swapchain after a resize.
  void present(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height, ImDrawData* ui);

  // Asks the next present() to also read the whole window back (image and UI).
  void request_capture() { capture_requested_ = true; }
  // The last capture as RGBA8 rows from the top, with its size; empty when none was taken
  // (or the surface does not allow reading its images).
  const std::vector<uint8_t>& capture() const { return capture_; }
  uint32_t capture_width() const { return capture_width_; }
  uint32_t capture_height() const { return capture_height_; }

 private:
  void release();
  void create_framebuffers();
  void destroy_framebuffers();
  void recreate();
  void record(uint32_t index, uint32_t width, uint32_t height, ImDrawData* ui, bool capture);

  gpu::Context& context_;
  GLFWwindow* window_;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  std::unique_ptr<gpu::Swapchain> swapchain_;
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  std::vector<VkFramebuffer> framebuffers_;
  VkDescriptorPool ui_pool_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  std::vector<VkSemaphore> rendered_;  // per swapchain image
  std::unique_ptr<gpu::Buffer> staging_;
  bool ui_initialised_ = false;
  bool capture_requested_ = false;
  std::unique_ptr<gpu::Buffer> capture_buffer_;
  std::vector<uint8_t> capture_;
  uint32_t capture_width_ = 0, capture_height_ = 0;
};

}  // namespace voxgi::viewer
