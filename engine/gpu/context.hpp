#pragma once
// The Vulkan 1.3 context: instance, device choice, one graphics+compute queue, memory,
// cached samplers, one-shot command submission and validation-layer message capture.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "engine/gpu/device_features.hpp"
#include "engine/gpu/memory.hpp"
#include "engine/gpu/pipeline_cache.hpp"

namespace voxgi::gpu {

struct ContextOptions {
  bool validation = false;                  // needs VK_LAYER_KHRONOS_validation
  bool synchronization_validation = false;  // implies validation
  // "" = automatic choice, else a device index ("1") or a case-insensitive substring of
  // the device name ("llvmpipe").
  std::string device;
  std::vector<const char*> instance_extensions;  // extra, e.g. for a window surface
  std::vector<const char*> device_extensions;    // extra, e.g. VK_KHR_swapchain
  // Where the pipeline cache lives between runs (PipelineCacheFile); "" keeps it in memory.
  std::filesystem::path pipeline_cache_dir = PipelineCacheFile::default_dir();
};

// Every linear kind also filters linearly between mips (so textureLod works on mip chains);
// the *Mipmapped kinds add anisotropic filtering where the device has it, which lavapipe
// applies even at an explicit LOD (taps around the sample), so lookups that mean one
// trilinear footprint (the voxel volumes) must not use them.
enum class SamplerKind {
  LinearClamp,
  LinearRepeat,
  NearestClamp,
  ShadowCompare,  // LESS_OR_EQUAL compare, linear, clamp-to-border opaque white
  LinearClampMipmapped,
  LinearRepeatMipmapped,
  // The scene's material textures: LinearRepeatMipmapped, but without anisotropic filtering
  // on CPU devices, where lavapipe's filter costs some 50 times a trilinear lookup (the Sponza
  // G-buffer: 10.5 s against 0.2 s at 8x8 pixels) and takes taps around the sample even at an
  // explicit LOD.
  SceneTexture,
};

class Context {
 public:
  // Throws Error when no suitable device exists, when options.device matches none (the
  // message lists the devices), or when validation is asked for but the layer is missing.
  explicit Context(const ContextOptions& options);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }

  const std::string& device_name() const { return device_name_; }
  VkPhysicalDeviceType device_type() const { return device_type_; }
  // One line: name, type, driver, Vulkan API version.
  std::string device_summary() const;
  const DeviceFeatures& features() const { return features_; }
  const VkPhysicalDeviceProperties& properties() const { return properties_; }
  bool has_debug_utils() const { return debug_utils_; }
  // Every pipeline is created through it; saved to disk when the context is released.
  VkPipelineCache pipeline_cache() const {
    return pipeline_cache_ ? pipeline_cache_->handle() : VK_NULL_HANDLE;
  }
  // The file it is kept in ("" when in memory only).
  std::filesystem::path pipeline_cache_path() const {
    return pipeline_cache_ ? pipeline_cache_->path() : std::filesystem::path();
  }
  // A named region of a command buffer for capture tools (VK_EXT_debug_utils); nothing where
  // the extension is absent. Every begin_label needs its end_label in the same buffer.
  void begin_label(VkCommandBuffer cmd, const std::string& name) const;
  void end_label(VkCommandBuffer cmd) const;

  Allocator& allocator() { return *allocator_; }

  // Created on first use, then cached for the lifetime of the context.
  VkSampler sampler(SamplerKind kind);

  // Records a one-shot command buffer, submits it and waits for the queue to finish it.
  // Serialised by a mutex, so any thread may call it.
  void immediate_submit(const std::function<void(VkCommandBuffer)>& record);
  // A resettable command pool of the queue family; for the caller's own command buffers
  // (used from one thread only).
  VkCommandPool command_pool() const { return command_pool_; }
  // vkQueueSubmit2 on the queue, serialised with immediate_submit (the queue is shared).
  void submit(const VkSubmitInfo2& info, VkFence fence);
  // vkQueueWaitIdle, serialised like submit().
  void wait_idle();

  // Validation-layer messages of severity WARNING or ERROR since the last clear.
  size_t validation_message_count() const;
  std::vector<std::string> validation_messages() const;
  void clear_validation_messages();
  // Called for every recorded message, in addition to recording it.
  void set_validation_observer(std::function<void(const std::string&)> observer);

  // Names an object for validation messages and debuggers; a no-op without debug utils.
  void set_debug_name(VkObjectType type, uint64_t handle, const std::string& name);

  // "index: name (type, driver, API x.y.z)" for every physical device.
  static std::vector<std::string> list_devices();

 private:
  void release();
  void create_instance(const ContextOptions& options);
  void choose_physical_device(const ContextOptions& options);
  void create_device(const ContextOptions& options);
  void query_unused_features();
  void record_validation_message(const std::string& message);
  static VKAPI_ATTR VkBool32 VKAPI_CALL debug_callback(
      VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  bool debug_utils_ = false;
  std::unique_ptr<PipelineCacheFile> pipeline_cache_;
  PFN_vkCmdBeginDebugUtilsLabelEXT begin_label_ = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT end_label_ = nullptr;
  PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;

  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties_{};
  std::string device_name_;
  std::string driver_name_;
  VkPhysicalDeviceType device_type_ = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  DeviceFeatures features_;
  bool sampler_anisotropy_ = false;

  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  std::unique_ptr<Allocator> allocator_;

  std::mutex submit_mutex_;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  VkCommandPool immediate_pool_ = VK_NULL_HANDLE;
  VkFence immediate_fence_ = VK_NULL_HANDLE;

  std::mutex sampler_mutex_;
  std::map<SamplerKind, VkSampler> samplers_;

  mutable std::mutex validation_mutex_;
  std::vector<std::string> validation_messages_;
  std::function<void(const std::string&)> validation_observer_;
};

}  // namespace voxgi::gpu
