#pragma once
// Compute and graphics pipelines. Resources are bound through push descriptors
// (VK_KHR_push_descriptor) in set 0; callers may add their own set layouts as sets 1..n
// (e.g. the scene's material set).

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace voxgi::gpu {

class Context;
class Buffer;

struct Binding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  VkShaderStageFlags stages = VK_SHADER_STAGE_ALL;
  uint32_t count = 1;
};

struct PipelineLayoutDesc {
  std::vector<Binding> bindings;                         // set 0, push descriptors
  std::vector<VkDescriptorSetLayout> extra_set_layouts;  // sets 1.., owned by the caller
  uint32_t push_constant_size = 0;                       // bytes, multiple of 4
  VkShaderStageFlags push_constant_stages = VK_SHADER_STAGE_ALL;
};

// The push-descriptor set layout and the pipeline layout built from a PipelineLayoutDesc.
class PipelineLayout {
 public:
  PipelineLayout(Context& context, const PipelineLayoutDesc& desc, const std::string& name);
  ~PipelineLayout();
  PipelineLayout(const PipelineLayout&) = delete;
  PipelineLayout& operator=(const PipelineLayout&) = delete;
  PipelineLayout(PipelineLayout&& other) noexcept;
  PipelineLayout& operator=(PipelineLayout&& other) noexcept;

  VkPipelineLayout handle() const { return layout_; }
  VkDescriptorSetLayout set_layout() const { return set_layout_; }
  uint32_t push_constant_size() const { return push_constant_size_; }
  VkShaderStageFlags push_constant_stages() const { return push_constant_stages_; }

 private:
  void destroy();
  Context* context_ = nullptr;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  uint32_t push_constant_size_ = 0;
  VkShaderStageFlags push_constant_stages_ = 0;
};

class ComputePipeline {
 public:
  // spirv: a compute shader with entry point "main". Throws Error on failure.
  ComputePipeline(Context& context, const std::vector<uint32_t>& spirv,
                  const PipelineLayoutDesc& layout, std::string name);
  ~ComputePipeline();
  ComputePipeline(const ComputePipeline&) = delete;
  ComputePipeline& operator=(const ComputePipeline&) = delete;
  ComputePipeline(ComputePipeline&& other) noexcept;
  ComputePipeline& operator=(ComputePipeline&& other) noexcept;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_.handle(); }
  VkDescriptorSetLayout set_layout() const { return layout_.set_layout(); }
  const std::string& name() const { return name_; }

  void bind(VkCommandBuffer cmd) const;
  // Throws Error when size exceeds the layout's push_constant_size.
  void push_constants(VkCommandBuffer cmd, const void* data, uint32_t size) const;
  template <typename T>
  void push_constants(VkCommandBuffer cmd, const T& value) const {
    push_constants(cmd, &value, static_cast<uint32_t>(sizeof(T)));
  }

  // Number of workgroups of size `local` that cover n items: ceil(n / local).
  static uint32_t groups(uint32_t n, uint32_t local) { return (n + local - 1) / local; }

 private:
  void destroy();
  Context* context_ = nullptr;
  PipelineLayout layout_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::string name_;
};

struct GraphicsPipelineDesc {
  std::vector<uint32_t> vertex;
  std::vector<uint32_t> geometry;  // optional
  std::vector<uint32_t> fragment;  // optional (depth-only passes)
  PipelineLayoutDesc layout;
  std::vector<VkVertexInputBindingDescription> vertex_bindings;
  std::vector<VkVertexInputAttributeDescription> vertex_attributes;
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cull = VK_CULL_MODE_NONE;
  VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  VkPolygonMode polygon = VK_POLYGON_MODE_FILL;
  bool depth_test = false;
  bool depth_write = false;
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
  bool depth_clamp = false;
  bool depth_bias = false;  // bias values are dynamic too (vkCmdSetDepthBias)
  float depth_bias_constant = 0.0f;
  float depth_bias_slope = 0.0f;
  // Overestimating conservative rasterization; throws Error when the device lacks it
  // (check Context::features().conservative_rasterization first).
  bool conservative_rasterization = false;
  std::vector<VkFormat> color_formats;
  VkFormat depth_format = VK_FORMAT_UNDEFINED;
  // One per color attachment; empty: no blending, write RGBA.
  std::vector<VkPipelineColorBlendAttachmentState> blend;
  uint32_t view_mask = 0;
  std::string name;
};

// Dynamic rendering; viewport, scissor and depth bias are dynamic state.
class GraphicsPipeline {
 public:
  GraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc);
  ~GraphicsPipeline();
  GraphicsPipeline(const GraphicsPipeline&) = delete;
  GraphicsPipeline& operator=(const GraphicsPipeline&) = delete;
  GraphicsPipeline(GraphicsPipeline&& other) noexcept;
  GraphicsPipeline& operator=(GraphicsPipeline&& other) noexcept;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_.handle(); }
  VkDescriptorSetLayout set_layout() const { return layout_.set_layout(); }
  const std::string& name() const { return name_; }

  // Binds the pipeline and, when depth bias is on, sets the desc's bias values.
  void bind(VkCommandBuffer cmd) const;
  void push_constants(VkCommandBuffer cmd, const void* data, uint32_t size) const;
  template <typename T>
  void push_constants(VkCommandBuffer cmd, const T& value) const {
    push_constants(cmd, &value, static_cast<uint32_t>(sizeof(T)));
  }
  // Sets viewport (0,0,w,h, depth 0..1) and scissor to the full extent.
  static void set_viewport(VkCommandBuffer cmd, uint32_t width, uint32_t height);

 private:
  void destroy();
  Context* context_ = nullptr;
  PipelineLayout layout_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  bool depth_bias_ = false;
  float depth_bias_constant_ = 0.0f;
  float depth_bias_slope_ = 0.0f;
  std::string name_;
};

// Collects descriptor writes for set 0 and pushes them (vkCmdPushDescriptorSetKHR).
// The referenced info structs live in the writer until push().
class DescriptorWriter {
 public:
  DescriptorWriter& storage_buffer(uint32_t binding, const Buffer& buffer, VkDeviceSize offset = 0,
                                   VkDeviceSize range = VK_WHOLE_SIZE);
  DescriptorWriter& uniform_buffer(uint32_t binding, const Buffer& buffer, VkDeviceSize offset = 0,
                                   VkDeviceSize range = VK_WHOLE_SIZE);
  // Raw-handle variants for buffers not owned by a gpu::Buffer.
  DescriptorWriter& buffer(uint32_t binding, VkDescriptorType type, VkBuffer buffer,
                           VkDeviceSize offset = 0, VkDeviceSize range = VK_WHOLE_SIZE);
  // Combined image sampler.
  DescriptorWriter& sampled_image(uint32_t binding, VkImageView view, VkImageLayout layout,
                                  VkSampler sampler);
  DescriptorWriter& storage_image(uint32_t binding, VkImageView view,
                                  VkImageLayout layout = VK_IMAGE_LAYOUT_GENERAL);
  // An array of combined image samplers starting at element 0.
  DescriptorWriter& image_array(uint32_t binding, std::vector<VkDescriptorImageInfo> images);

  void push(VkCommandBuffer cmd, VkPipelineBindPoint bind_point, VkPipelineLayout layout,
            uint32_t set = 0);
  void clear();
  bool empty() const { return writes_.empty(); }

 private:
  struct Pending {
    uint32_t binding;
    VkDescriptorType type;
    size_t first;  // index into buffers_ or images_
    uint32_t count;
    bool is_buffer;
  };
  std::vector<Pending> writes_;
  std::vector<VkDescriptorBufferInfo> buffers_;
  std::vector<VkDescriptorImageInfo> images_;
};

// A shader module for the lifetime of a pipeline creation; throws Error on failure.
VkShaderModule create_shader_module(Context& context, const std::vector<uint32_t>& spirv,
                                    const std::string& name);

}  // namespace voxgi::gpu
