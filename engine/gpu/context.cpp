#include "engine/gpu/context.hpp"

#include <cstring>
#include <iostream>

#include "engine/gpu/device_selection.hpp"
#include "engine/gpu/error.hpp"
#include "engine/gpu/extension_functions.hpp"

namespace voxgi::gpu {

namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

std::vector<VkExtensionProperties> instance_extensions(const char* layer) {
  uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data());
  return extensions;
}

bool contains(const std::vector<VkExtensionProperties>& extensions, const char* name) {
  for (const auto& extension : extensions) {
    if (std::strcmp(extension.extensionName, name) == 0) return true;
  }
  return false;
}

bool has_layer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const auto& layer : layers) {
    if (std::strcmp(layer.layerName, name) == 0) return true;
  }
  return false;
}

void require_instance_version() {
  uint32_t version = VK_API_VERSION_1_0;
  vkEnumerateInstanceVersion(&version);
  if (version < VK_API_VERSION_1_3) {
    throw Error("the Vulkan loader supports only API " +
                std::to_string(VK_API_VERSION_MAJOR(version)) + "." +
                std::to_string(VK_API_VERSION_MINOR(version)) +
                ", voxgi needs 1.3: update libvulkan1 and the GPU driver");
  }
}

VkApplicationInfo application_info() {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "voxgi";
  app.applicationVersion = VK_MAKE_VERSION(0, 1, 0);
  app.pEngineName = "voxgi";
  app.engineVersion = VK_MAKE_VERSION(0, 1, 0);
  app.apiVersion = VK_API_VERSION_1_3;
  return app;
}

}  // namespace

Context::Context(const ContextOptions& options) {
  try {
    create_instance(options);
    choose_physical_device(options);
    create_device(options);
  } catch (...) {
    release();
    throw;
  }
}

void Context::create_instance(const ContextOptions& options) {
  require_instance_version();
  bool validation = options.validation || options.synchronization_validation;
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  auto available = instance_extensions(nullptr);
  if (validation) {
    if (!has_layer(kValidationLayer)) {
      throw Error(std::string("validation was requested but ") + kValidationLayer +
                  " is missing: install vulkan-validationlayers");
    }
    layers.push_back(kValidationLayer);
    auto layer_extensions = instance_extensions(kValidationLayer);
    available.insert(available.end(), layer_extensions.begin(), layer_extensions.end());
  }
  debug_utils_ = contains(available, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debug_utils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  bool validation_features =
      validation && contains(available, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  if (validation_features) extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  VkInstanceCreateFlags flags = 0;
  if (contains(available, VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
    extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
    flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
  }
  for (const char* name : options.instance_extensions) {
    if (!contains(available, name)) {
      throw Error(std::string("Vulkan instance extension ") + name +
                  " is not available: install or update the Vulkan loader and drivers");
    }
    bool present = false;
    for (const char* e : extensions) present = present || std::strcmp(e, name) == 0;
    if (!present) extensions.push_back(name);
  }

  VkApplicationInfo app = application_info();
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.flags = flags;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();

  VkDebugUtilsMessengerCreateInfoEXT messenger{
      VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = &Context::debug_callback;
  messenger.pUserData = this;

  VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &sync;

  const void* chain = nullptr;
  if (validation && debug_utils_) chain = &messenger;
  if (options.synchronization_validation) {
    if (!validation_features) {
      throw Error(
          "synchronization validation was requested but the validation layer lacks "
          "VK_EXT_validation_features: update vulkan-validationlayers");
    }
    features.pNext = chain;
    chain = &features;
  }
  info.pNext = chain;
  check(vkCreateInstance(&info, nullptr, &instance_), "vkCreateInstance");

  if (debug_utils_) {
    set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
    begin_label_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
    end_label_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
    if (!begin_label_ || !end_label_) begin_label_ = nullptr, end_label_ = nullptr;
    if (validation) {
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
      if (create)
        check(create(instance_, &messenger, nullptr, &messenger_),
              "creating the "
              "debug messenger");
    }
  }
}

void Context::choose_physical_device(const ContextOptions& options) {
  auto devices = describe_devices(instance_);
  const PhysicalDeviceInfo& chosen = choose_device(devices, options.device);
  physical_device_ = chosen.handle;
  properties_ = chosen.properties;
  device_name_ = chosen.properties.deviceName;
  driver_name_ = chosen.driver;
  device_type_ = chosen.properties.deviceType;
  queue_family_ = chosen.queue_family;
}

// Features graphs may test but no pass enables yet: supported, as the driver reports them.
// A structure is chained only where its extension exists, as the specification requires.
void Context::query_unused_features() {
  VkPhysicalDeviceRayTracingPipelineFeaturesKHR ray_tracing{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_FEATURES_KHR};
  VkPhysicalDeviceRayQueryFeaturesKHR ray_query{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR acceleration{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceMeshShaderFeaturesEXT mesh{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MESH_SHADER_FEATURES_EXT};
  VkPhysicalDeviceFeatures2 has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  void** next = &has.pNext;
  const auto chain = [&](const char* extension, auto& features) {
    if (!has_device_extension(physical_device_, extension)) return false;
    *next = &features;
    next = &features.pNext;
    return true;
  };
  const bool has_ray_tracing = chain(VK_KHR_RAY_TRACING_PIPELINE_EXTENSION_NAME, ray_tracing);
  const bool has_ray_query = chain(VK_KHR_RAY_QUERY_EXTENSION_NAME, ray_query);
  const bool has_acceleration = chain(VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, acceleration);
  const bool has_mesh = chain(VK_EXT_MESH_SHADER_EXTENSION_NAME, mesh);
  vkGetPhysicalDeviceFeatures2(physical_device_, &has);
  features_.ray_tracing_pipeline = has_ray_tracing && ray_tracing.rayTracingPipeline;
  features_.ray_query = has_ray_query && ray_query.rayQuery;
  features_.acceleration_structure = has_acceleration && acceleration.accelerationStructure;
  features_.mesh_shader = has_mesh && mesh.meshShader;
}

void Context::create_device(const ContextOptions& options) {
  // What the device has.
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT has_atomic{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  VkPhysicalDeviceVulkan13Features has13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features has12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan11Features has11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceFeatures2 has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  bool atomic_float_ext =
      has_device_extension(physical_device_, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
  bool conservative_ext =
      has_device_extension(physical_device_, VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);
  has.pNext = &has11;
  has11.pNext = &has12;
  has12.pNext = &has13;
  if (atomic_float_ext) has13.pNext = &has_atomic;
  vkGetPhysicalDeviceFeatures2(physical_device_, &has);

  // What we turn on: everything the renderer uses that the device has.
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomic{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceFeatures2 f{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  f13.dynamicRendering = has13.dynamicRendering;
  f13.synchronization2 = has13.synchronization2;
  f13.maintenance4 = has13.maintenance4;
  f12.scalarBlockLayout = has12.scalarBlockLayout;
  f12.runtimeDescriptorArray = has12.runtimeDescriptorArray;
  f12.descriptorBindingPartiallyBound = has12.descriptorBindingPartiallyBound;
  f12.shaderSampledImageArrayNonUniformIndexing = has12.shaderSampledImageArrayNonUniformIndexing;
  f12.descriptorBindingVariableDescriptorCount = has12.descriptorBindingVariableDescriptorCount;
  f12.hostQueryReset = has12.hostQueryReset;
  f12.shaderOutputLayer = has12.shaderOutputLayer;
  f12.shaderOutputViewportIndex = has12.shaderOutputViewportIndex;
  f12.storageBuffer8BitAccess = has12.storageBuffer8BitAccess;
  f12.shaderInt8 = has12.shaderInt8;
  f11.shaderDrawParameters = has11.shaderDrawParameters;
  f11.multiview = has11.multiview;  // GraphicsPipelineDesc::view_mask
  const VkPhysicalDeviceFeatures& h = has.features;
  VkPhysicalDeviceFeatures& e = f.features;
  e.geometryShader = h.geometryShader;
  e.fragmentStoresAndAtomics = h.fragmentStoresAndAtomics;
  e.vertexPipelineStoresAndAtomics = h.vertexPipelineStoresAndAtomics;
  e.shaderStorageImageWriteWithoutFormat = h.shaderStorageImageWriteWithoutFormat;
  e.shaderStorageImageReadWithoutFormat = h.shaderStorageImageReadWithoutFormat;
  e.shaderImageGatherExtended = h.shaderImageGatherExtended;
  e.samplerAnisotropy = h.samplerAnisotropy;
  e.fillModeNonSolid = h.fillModeNonSolid;
  e.depthClamp = h.depthClamp;
  e.independentBlend = h.independentBlend;
  e.multiViewport = h.multiViewport;
  e.shaderInt64 = h.shaderInt64;
  e.imageCubeArray = h.imageCubeArray;
  f.pNext = &f11;
  f11.pNext = &f12;
  f12.pNext = &f13;

  std::vector<const char*> extensions{VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  if (atomic_float_ext &&
      (has_atomic.shaderBufferFloat32AtomicAdd || has_atomic.shaderImageFloat32AtomicAdd)) {
    extensions.push_back(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
    atomic.shaderBufferFloat32Atomics = has_atomic.shaderBufferFloat32Atomics;
    atomic.shaderBufferFloat32AtomicAdd = has_atomic.shaderBufferFloat32AtomicAdd;
    atomic.shaderImageFloat32Atomics = has_atomic.shaderImageFloat32Atomics;
    atomic.shaderImageFloat32AtomicAdd = has_atomic.shaderImageFloat32AtomicAdd;
    f13.pNext = &atomic;
    features_.atomic_float_add_buffer = atomic.shaderBufferFloat32AtomicAdd;
    features_.atomic_float_add_image = atomic.shaderImageFloat32AtomicAdd;
  }
  if (conservative_ext) {
    extensions.push_back(VK_EXT_CONSERVATIVE_RASTERIZATION_EXTENSION_NAME);
    features_.conservative_rasterization = true;
  }
  for (const char* name : options.device_extensions) {
    if (!has_device_extension(physical_device_, name)) {
      throw Error(std::string("Vulkan device extension ") + name + " is not supported by " +
                  device_name_ + ": choose another --device or update the driver");
    }
    bool present = false;
    for (const char* x : extensions) present = present || std::strcmp(x, name) == 0;
    if (!present) extensions.push_back(name);
  }

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue.queueFamilyIndex = queue_family_;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &f;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue;
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  check(vkCreateDevice(physical_device_, &info, nullptr, &device_),
        ("vkCreateDevice on " + device_name_).c_str());
  pipeline_cache_ =
      std::make_unique<PipelineCacheFile>(device_, properties_, options.pipeline_cache_dir);
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
  load_extension_functions(instance_);

  features_.geometry_shader = e.geometryShader;
  features_.shader_int64 = e.shaderInt64;
  query_unused_features();
  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, families.data());
  features_.timestamps =
      families[queue_family_].timestampValidBits > 0 && properties_.limits.timestampPeriod > 0.0f;
  features_.timestamp_period_ns = properties_.limits.timestampPeriod;
  VkPhysicalDevicePushDescriptorPropertiesKHR push{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &push;
  vkGetPhysicalDeviceProperties2(physical_device_, &props);
  features_.max_push_descriptors = push.maxPushDescriptors;
  sampler_anisotropy_ = e.samplerAnisotropy;

  allocator_ = std::make_unique<DedicatedAllocator>(physical_device_, device_);

  VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool.queueFamilyIndex = queue_family_;
  check(vkCreateCommandPool(device_, &pool, nullptr, &command_pool_), "vkCreateCommandPool");
  pool.flags |= VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  check(vkCreateCommandPool(device_, &pool, nullptr, &immediate_pool_), "vkCreateCommandPool");
  VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vkCreateFence(device_, &fence, nullptr, &immediate_fence_), "vkCreateFence");
}

Context::~Context() {
  release();
}

void Context::release() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    for (auto& [kind, sampler] : samplers_) vkDestroySampler(device_, sampler, nullptr);
    samplers_.clear();
    if (immediate_fence_) vkDestroyFence(device_, immediate_fence_, nullptr);
    if (immediate_pool_) vkDestroyCommandPool(device_, immediate_pool_, nullptr);
    if (command_pool_) vkDestroyCommandPool(device_, command_pool_, nullptr);
    immediate_fence_ = VK_NULL_HANDLE;
    immediate_pool_ = command_pool_ = VK_NULL_HANDLE;
    allocator_.reset();
    pipeline_cache_.reset();  // written to disk here
    vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) {
    vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
  }
}

std::string Context::device_summary() const {
  uint32_t v = properties_.apiVersion;
  return device_name_ + " (" + device_type_name(device_type_) + ", " + driver_name_ + ", API " +
         std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v)) + ")";
}

VkSampler Context::sampler(SamplerKind kind) {
  std::lock_guard lock(sampler_mutex_);
  auto found = samplers_.find(kind);
  if (found != samplers_.end()) return found->second;
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = VK_FILTER_LINEAR;
  info.minFilter = VK_FILTER_LINEAR;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.minLod = 0.0f;
  info.maxLod = VK_LOD_CLAMP_NONE;
  info.borderColor = VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
  const char* name = "";
  switch (kind) {
    case SamplerKind::LinearClamp:
      name = "sampler.linear_clamp";
      break;
    case SamplerKind::LinearRepeat:
      name = "sampler.linear_repeat";
      info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
      break;
    case SamplerKind::NearestClamp:
      name = "sampler.nearest_clamp";
      info.magFilter = info.minFilter = VK_FILTER_NEAREST;
      info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
      break;
    case SamplerKind::ShadowCompare:
      name = "sampler.shadow_compare";
      info.addressModeU = info.addressModeV = info.addressModeW =
          VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
      info.borderColor = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
      info.compareEnable = VK_TRUE;
      info.compareOp = VK_COMPARE_OP_LESS_OR_EQUAL;
      info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
      break;
    case SamplerKind::SceneTexture:
      name = "sampler.scene_texture";
      info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
      if (sampler_anisotropy_ && device_type_ != VK_PHYSICAL_DEVICE_TYPE_CPU) {
        info.anisotropyEnable = VK_TRUE;
        info.maxAnisotropy = std::min(8.0f, properties_.limits.maxSamplerAnisotropy);
      }
      break;
    case SamplerKind::LinearClampMipmapped:
    case SamplerKind::LinearRepeatMipmapped:
      name = kind == SamplerKind::LinearClampMipmapped ? "sampler.linear_clamp_mipmapped"
                                                       : "sampler.linear_repeat_mipmapped";
      if (kind == SamplerKind::LinearRepeatMipmapped) {
        info.addressModeU = info.addressModeV = info.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
      }
      if (sampler_anisotropy_) {
        info.anisotropyEnable = VK_TRUE;
        info.maxAnisotropy = std::min(8.0f, properties_.limits.maxSamplerAnisotropy);
      }
      break;
  }
  VkSampler sampler = VK_NULL_HANDLE;
  check(vkCreateSampler(device_, &info, nullptr, &sampler), "vkCreateSampler");
  set_debug_name(VK_OBJECT_TYPE_SAMPLER, reinterpret_cast<uint64_t>(sampler), name);
  samplers_[kind] = sampler;
  return sampler;
}

void Context::immediate_submit(const std::function<void(VkCommandBuffer)>& record) {
  std::lock_guard lock(submit_mutex_);
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = immediate_pool_;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(device_, &alloc, &cmd), "vkAllocateCommandBuffers");
  try {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
    record(cmd);
    check(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    check(vkQueueSubmit2(queue_, 1, &submit, immediate_fence_), "vkQueueSubmit2");
    check(vkWaitForFences(device_, 1, &immediate_fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(device_, 1, &immediate_fence_), "vkResetFences");
  } catch (...) {
    vkFreeCommandBuffers(device_, immediate_pool_, 1, &cmd);
    throw;
  }
  vkFreeCommandBuffers(device_, immediate_pool_, 1, &cmd);
}

void Context::submit(const VkSubmitInfo2& info, VkFence fence) {
  std::lock_guard lock(submit_mutex_);
  check(vkQueueSubmit2(queue_, 1, &info, fence), "vkQueueSubmit2");
}

void Context::wait_idle() {
  std::lock_guard lock(submit_mutex_);
  check(vkQueueWaitIdle(queue_), "vkQueueWaitIdle");
}

size_t Context::validation_message_count() const {
  std::lock_guard lock(validation_mutex_);
  return validation_messages_.size();
}

std::vector<std::string> Context::validation_messages() const {
  std::lock_guard lock(validation_mutex_);
  return validation_messages_;
}

void Context::clear_validation_messages() {
  std::lock_guard lock(validation_mutex_);
  validation_messages_.clear();
}

void Context::set_validation_observer(std::function<void(const std::string&)> observer) {
  std::lock_guard lock(validation_mutex_);
  validation_observer_ = std::move(observer);
}

void Context::record_validation_message(const std::string& message) {
  std::cerr << "vulkan validation: " << message << std::endl;
  std::function<void(const std::string&)> observer;
  {
    std::lock_guard lock(validation_mutex_);
    validation_messages_.push_back(message);
    observer = validation_observer_;
  }
  if (observer) observer(message);
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::debug_callback(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  auto* context = static_cast<Context*>(user);
  std::string message = data && data->pMessage ? data->pMessage : "(no message)";
  context->record_validation_message(message);
  return VK_FALSE;
}

void Context::set_debug_name(VkObjectType type, uint64_t handle, const std::string& name) {
  if (!set_object_name_ || !device_ || handle == 0 || name.empty()) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  set_object_name_(device_, &info);
}

std::vector<std::string> Context::list_devices() {
  require_instance_version();
  VkApplicationInfo app = application_info();
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  std::vector<const char*> extensions;
  if (contains(instance_extensions(nullptr), VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
    extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
    info.flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
  }
  info.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
  std::vector<std::string> lines;
  try {
    for (const auto& device : describe_devices(instance)) lines.push_back(describe(device));
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return lines;
}

void Context::begin_label(VkCommandBuffer cmd, const std::string& name) const {
  if (!begin_label_) return;
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = name.c_str();
  begin_label_(cmd, &label);
}

void Context::end_label(VkCommandBuffer cmd) const {
  if (end_label_) end_label_(cmd);
}

}  // namespace voxgi::gpu
