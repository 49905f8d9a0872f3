#include "apps/viewer/presenter.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <cstring>
#include <iostream>

#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"
#include "engine/gpu/sync.hpp"

namespace voxgi::viewer {
namespace {

void check_ui_result(VkResult result) {
  if (result != VK_SUCCESS)
    std::cerr << "voxgi-viewer: ImGui Vulkan call failed: " << result << "\n";
}

VkExtent2D framebuffer_extent(GLFWwindow* window) {
  int w = 0, h = 0;
  glfwGetFramebufferSize(window, &w, &h);
  return {static_cast<uint32_t>(std::max(w, 1)), static_cast<uint32_t>(std::max(h, 1))};
}

}  // namespace

Presenter::Presenter(gpu::Context& context, GLFWwindow* window)
    : context_(context), window_(window) {
  try {
    gpu::check(glfwCreateWindowSurface(context_.instance(), window_, nullptr, &surface_),
               "glfwCreateWindowSurface");
    swapchain_ = std::make_unique<gpu::Swapchain>(context_, surface_, framebuffer_extent(window_));

    VkAttachmentDescription color{};
    color.format = swapchain_->format();
    color.samples = VK_SAMPLE_COUNT_1_BIT;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // keeps the image copied in before
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    color.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    color.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    color.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &ref;
    VkSubpassDependency after_copy{};
    after_copy.srcSubpass = VK_SUBPASS_EXTERNAL;
    after_copy.dstSubpass = 0;
    after_copy.srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    after_copy.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    after_copy.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    after_copy.dstAccessMask =
        VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    VkRenderPassCreateInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    pass.attachmentCount = 1;
    pass.pAttachments = &color;
    pass.subpassCount = 1;
    pass.pSubpasses = &subpass;
    pass.dependencyCount = 1;
    pass.pDependencies = &after_copy;
    gpu::check(vkCreateRenderPass(context_.device(), &pass, nullptr, &render_pass_),
               "vkCreateRenderPass");
    create_framebuffers();

    VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool.queueFamilyIndex = context_.queue_family();
    gpu::check(vkCreateCommandPool(context_.device(), &pool, nullptr, &pool_),
               "vkCreateCommandPool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool_;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    gpu::check(vkAllocateCommandBuffers(context_.device(), &alloc, &cmd_),
               "vkAllocateCommandBuffers");
    VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    gpu::check(vkCreateFence(context_.device(), &fence, nullptr, &fence_), "vkCreateFence");
    VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    gpu::check(vkCreateSemaphore(context_.device(), &semaphore, nullptr, &acquired_),
               "vkCreateSemaphore");

    VkDescriptorPoolSize sizes{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16};
    VkDescriptorPoolCreateInfo ui_pool{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    ui_pool.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
    ui_pool.maxSets = 16;
    ui_pool.poolSizeCount = 1;
    ui_pool.pPoolSizes = &sizes;
    gpu::check(vkCreateDescriptorPool(context_.device(), &ui_pool, nullptr, &ui_pool_),
               "vkCreateDescriptorPool");

    ImGui_ImplVulkan_InitInfo init{};
    init.Instance = context_.instance();
    init.PhysicalDevice = context_.physical_device();
    init.Device = context_.device();
    init.QueueFamily = context_.queue_family();
    init.Queue = context_.queue();
    init.DescriptorPool = ui_pool_;
    init.Subpass = 0;
    init.MinImageCount = swapchain_->min_image_count();
    init.ImageCount = std::max(swapchain_->image_count(), swapchain_->min_image_count());
    init.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
    init.CheckVkResultFn = &check_ui_result;
    if (!ImGui_ImplVulkan_Init(&init, render_pass_)) {
      throw gpu::Error("ImGui's Vulkan backend failed to initialise");
    }
    ui_initialised_ = true;
    context_.immediate_submit(
        [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); });
    ImGui_ImplVulkan_DestroyFontUploadObjects();
  } catch (...) {
    release();
    throw;
  }
}

Presenter::~Presenter() {
  release();
}

void Presenter::release() {
  VkDevice device = context_.device();
  context_.wait_idle();
  if (ui_initialised_) ImGui_ImplVulkan_Shutdown();
  ui_initialised_ = false;
  staging_.reset();
  capture_buffer_.reset();
  for (VkSemaphore s : rendered_) vkDestroySemaphore(device, s, nullptr);
  rendered_.clear();
  if (acquired_) vkDestroySemaphore(device, acquired_, nullptr);
  if (fence_) vkDestroyFence(device, fence_, nullptr);
  if (pool_) vkDestroyCommandPool(device, pool_, nullptr);
  if (ui_pool_) vkDestroyDescriptorPool(device, ui_pool_, nullptr);
  destroy_framebuffers();
  if (render_pass_) vkDestroyRenderPass(device, render_pass_, nullptr);
  swapchain_.reset();
  if (surface_) vkDestroySurfaceKHR(context_.instance(), surface_, nullptr);
  acquired_ = VK_NULL_HANDLE;
  fence_ = VK_NULL_HANDLE;
  pool_ = VK_NULL_HANDLE;
  ui_pool_ = VK_NULL_HANDLE;
  render_pass_ = VK_NULL_HANDLE;
  surface_ = VK_NULL_HANDLE;
}

void Presenter::create_framebuffers() {
  for (uint32_t i = 0; i < swapchain_->image_count(); ++i) {
    VkImageView view = swapchain_->view(i);
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = render_pass_;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = swapchain_->extent().width;
    info.height = swapchain_->extent().height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    gpu::check(vkCreateFramebuffer(context_.device(), &info, nullptr, &framebuffer),
               "vkCreateFramebuffer");
    framebuffers_.push_back(framebuffer);
  }
  VkSemaphoreCreateInfo semaphore{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  while (rendered_.size() < swapchain_->image_count()) {
    VkSemaphore s = VK_NULL_HANDLE;
    gpu::check(vkCreateSemaphore(context_.device(), &semaphore, nullptr, &s), "vkCreateSemaphore");
    rendered_.push_back(s);
  }
}

void Presenter::destroy_framebuffers() {
  for (VkFramebuffer f : framebuffers_) vkDestroyFramebuffer(context_.device(), f, nullptr);
  framebuffers_.clear();
}

void Presenter::recreate() {
  context_.wait_idle();
  destroy_framebuffers();
  swapchain_->recreate(framebuffer_extent(window_));
  create_framebuffers();
  ImGui_ImplVulkan_SetMinImageCount(swapchain_->min_image_count());
}

void Presenter::record(uint32_t index, uint32_t width, uint32_t height, ImDrawData* ui,
                       bool capture) {
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  gpu::check(vkBeginCommandBuffer(cmd_, &begin), "vkBeginCommandBuffer");
  VkImage image = swapchain_->image(index);
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};

  using gpu::BarrierScope;
  constexpr BarrierScope kNothing{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_NONE};
  constexpr BarrierScope kClearWrite{VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
  constexpr BarrierScope kCopyWrite{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT};
  constexpr VkImageLayout kTransferDst = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  gpu::image_barrier(cmd_, image, range, VK_IMAGE_LAYOUT_UNDEFINED, kTransferDst, kNothing,
                     kClearWrite);

  const VkClearColorValue background{{0.08f, 0.08f, 0.09f, 1.0f}};
  vkCmdClearColorImage(cmd_, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &background, 1, &range);

  const VkExtent2D extent = swapchain_->extent();
  const uint32_t copy_w = std::min(width, extent.width);
  const uint32_t copy_h = std::min(height, extent.height);
  if (staging_ && copy_w > 0 && copy_h > 0) {
    // The clear and the copy both write the image.
    gpu::image_barrier(cmd_, image, range, kTransferDst, kTransferDst, kClearWrite, kCopyWrite);
    VkBufferImageCopy copy{};
    copy.bufferRowLength = width;
    copy.bufferImageHeight = height;
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {copy_w, copy_h, 1};
    vkCmdCopyBufferToImage(cmd_, staging_->handle(), image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &copy);
  }
  // The render pass's external dependency orders the UI after the transfers.
  gpu::image_barrier(
      cmd_, image, range, kTransferDst, kTransferDst,
      {VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT},
      {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
       VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT});

  VkRenderPassBeginInfo pass{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  pass.renderPass = render_pass_;
  pass.framebuffer = framebuffers_[index];
  pass.renderArea = {{0, 0}, extent};
  vkCmdBeginRenderPass(cmd_, &pass, VK_SUBPASS_CONTENTS_INLINE);
  if (ui) ImGui_ImplVulkan_RenderDrawData(ui, cmd_);
  vkCmdEndRenderPass(cmd_);
  if (capture) {
    gpu::image_barrier(
        cmd_, image, range, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
        {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT},
        {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT});
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd_, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           capture_buffer_->handle(), 1, &copy);
    gpu::image_barrier(cmd_, image, range, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                       {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE}, kNothing);
    gpu::memory_barrier(cmd_, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  }
  gpu::check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");
}

void Presenter::present(const std::vector<uint8_t>& bytes, uint32_t width, uint32_t height,
                        ImDrawData* ui) {
  const VkExtent2D wanted = framebuffer_extent(window_);
  if (wanted.width != swapchain_->extent().width || wanted.height != swapchain_->extent().height) {
    recreate();
  }
  const VkDeviceSize size = static_cast<VkDeviceSize>(width) * height * 4;
  if (size > 0 && bytes.size() >= size) {
    if (!staging_ || staging_->size() < size) {
      context_.wait_idle();
      staging_ = std::make_unique<gpu::Buffer>(context_, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                               gpu::MemoryUsage::CpuToGpu, "viewer.image");
    }
    staging_->upload(bytes.data(), size);
  } else {
    width = height = 0;
  }

  std::optional<uint32_t> index = swapchain_->acquire(acquired_);
  if (!index) {
    recreate();
    return;  // the next frame draws into the new swapchain
  }
  gpu::check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  const VkExtent2D extent = swapchain_->extent();
  const bool capture = capture_requested_ && swapchain_->readable();
  if (capture_requested_ && !swapchain_->readable()) {
    std::cerr << "voxgi-viewer: this window surface does not allow reading its images\n";
  }
  capture_requested_ = false;
  if (capture) {
    const VkDeviceSize capture_size = VkDeviceSize(extent.width) * extent.height * 4;
    if (!capture_buffer_ || capture_buffer_->size() < capture_size) {
      capture_buffer_ =
          std::make_unique<gpu::Buffer>(context_, capture_size, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                        gpu::MemoryUsage::GpuToCpu, "viewer.capture");
    }
  }
  record(*index, width, height, ui, capture);

  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = acquired_;
  wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = rendered_[*index];
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmd_info.commandBuffer = cmd_;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmd_info;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  context_.submit(submit, fence_);
  if (!swapchain_->present(*index, rendered_[*index])) recreate();
  // One frame in flight: the staging buffer and command buffer are reused next frame.
  gpu::check(vkWaitForFences(context_.device(), 1, &fence_, VK_TRUE, UINT64_MAX),
             "vkWaitForFences");
  gpu::check(vkResetFences(context_.device(), 1, &fence_), "vkResetFences");
  if (capture) {
    capture_width_ = extent.width;
    capture_height_ = extent.height;
    capture_.resize(size_t(extent.width) * extent.height * 4);
    capture_buffer_->download(capture_.data(), capture_.size());
    if (swapchain_->bgr_order()) {
      for (size_t i = 0; i < capture_.size(); i += 4) std::swap(capture_[i], capture_[i + 2]);
    }
  }
}

}  // namespace voxgi::viewer
