#include "engine/gpu/pipeline.hpp"

#include <utility>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"
#include "engine/gpu/extension_functions.hpp"

namespace voxgi::gpu {

VkShaderModule create_shader_module(Context& context, const std::vector<uint32_t>& spirv,
                                    const std::string& name) {
  if (spirv.empty() || spirv[0] != 0x07230203u) {
    throw Error("pipeline \"" + name + "\": shader code is not SPIR-V (" +
                (spirv.empty() ? std::string("empty") : std::string("bad magic number")) +
                "); expected the output of ShaderCompiler::compile");
  }
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.size() * sizeof(uint32_t);
  info.pCode = spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  check(vkCreateShaderModule(context.device(), &info, nullptr, &module),
        ("vkCreateShaderModule for \"" + name + "\"").c_str());
  return module;
}

namespace {

// Destroys the shader modules of one pipeline creation, whatever happens.
struct ModuleList {
  VkDevice device;
  std::vector<VkShaderModule> modules;
  ~ModuleList() {
    for (VkShaderModule module : modules) vkDestroyShaderModule(device, module, nullptr);
  }
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// PipelineLayout

PipelineLayout::PipelineLayout(Context& context, const PipelineLayoutDesc& desc,
                               const std::string& name)
    : context_(&context),
      push_constant_size_(desc.push_constant_size),
      push_constant_stages_(desc.push_constant_stages) {
  if (desc.push_constant_size % 4 != 0 ||
      desc.push_constant_size > context.properties().limits.maxPushConstantsSize) {
    throw Error("pipeline \"" + name + "\": push_constant_size " +
                std::to_string(desc.push_constant_size) + " must be a multiple of 4 and at most " +
                std::to_string(context.properties().limits.maxPushConstantsSize));
  }
  uint32_t descriptors = 0;
  std::vector<VkDescriptorSetLayoutBinding> bindings;
  for (const Binding& b : desc.bindings) {
    VkDescriptorSetLayoutBinding binding{};
    binding.binding = b.binding;
    binding.descriptorType = b.type;
    binding.descriptorCount = b.count;
    binding.stageFlags = b.stages;
    bindings.push_back(binding);
    descriptors += b.count;
  }
  if (descriptors > context.features().max_push_descriptors) {
    throw Error("pipeline \"" + name + "\": " + std::to_string(descriptors) +
                " push descriptors, the device allows " +
                std::to_string(context.features().max_push_descriptors));
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  set_info.bindingCount = static_cast<uint32_t>(bindings.size());
  set_info.pBindings = bindings.data();
  check(vkCreateDescriptorSetLayout(context.device(), &set_info, nullptr, &set_layout_),
        ("vkCreateDescriptorSetLayout for \"" + name + "\"").c_str());

  std::vector<VkDescriptorSetLayout> sets{set_layout_};
  sets.insert(sets.end(), desc.extra_set_layouts.begin(), desc.extra_set_layouts.end());
  VkPushConstantRange push{desc.push_constant_stages, 0, desc.push_constant_size};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = static_cast<uint32_t>(sets.size());
  info.pSetLayouts = sets.data();
  info.pushConstantRangeCount = desc.push_constant_size > 0 ? 1 : 0;
  info.pPushConstantRanges = &push;
  VkResult result = vkCreatePipelineLayout(context.device(), &info, nullptr, &layout_);
  if (result != VK_SUCCESS) {
    destroy();
    check(result, ("vkCreatePipelineLayout for \"" + name + "\"").c_str());
  }
}

PipelineLayout::~PipelineLayout() {
  destroy();
}

PipelineLayout::PipelineLayout(PipelineLayout&& other) noexcept
    : context_(other.context_),
      set_layout_(std::exchange(other.set_layout_, VK_NULL_HANDLE)),
      layout_(std::exchange(other.layout_, VK_NULL_HANDLE)),
      push_constant_size_(other.push_constant_size_),
      push_constant_stages_(other.push_constant_stages_) {}

PipelineLayout& PipelineLayout::operator=(PipelineLayout&& other) noexcept {
  if (this != &other) {
    destroy();
    context_ = other.context_;
    set_layout_ = std::exchange(other.set_layout_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    push_constant_size_ = other.push_constant_size_;
    push_constant_stages_ = other.push_constant_stages_;
  }
  return *this;
}

void PipelineLayout::destroy() {
  if (!context_) return;
  if (layout_) vkDestroyPipelineLayout(context_->device(), layout_, nullptr);
  if (set_layout_) vkDestroyDescriptorSetLayout(context_->device(), set_layout_, nullptr);
  layout_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
}

namespace {

void push(VkCommandBuffer cmd, const PipelineLayout& layout, const std::string& name,
          const void* data, uint32_t size) {
  if (size > layout.push_constant_size()) {
    throw Error("pipeline \"" + name + "\": " + std::to_string(size) +
                " bytes of push constants, the layout declares " +
                std::to_string(layout.push_constant_size()));
  }
  if (size == 0) return;
  vkCmdPushConstants(cmd, layout.handle(), layout.push_constant_stages(), 0, size, data);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// ComputePipeline

ComputePipeline::ComputePipeline(Context& context, const std::vector<uint32_t>& spirv,
                                 const PipelineLayoutDesc& layout, std::string name)
    : context_(&context), layout_(context, layout, name), name_(std::move(name)) {
  ModuleList modules{context.device(), {create_shader_module(context, spirv, name_)}};
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = modules.modules[0];
  info.stage.pName = "main";
  info.layout = layout_.handle();
  check(vkCreateComputePipelines(context.device(), context.pipeline_cache(), 1, &info, nullptr,
                                 &pipeline_),
        ("vkCreateComputePipelines for \"" + name_ + "\"").c_str());
  context.set_debug_name(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline_), name_);
}

ComputePipeline::~ComputePipeline() {
  destroy();
}

ComputePipeline::ComputePipeline(ComputePipeline&& other) noexcept
    : context_(other.context_),
      layout_(std::move(other.layout_)),
      pipeline_(std::exchange(other.pipeline_, VK_NULL_HANDLE)),
      name_(std::move(other.name_)) {}

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& other) noexcept {
  if (this != &other) {
    destroy();
    context_ = other.context_;
    layout_ = std::move(other.layout_);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
    name_ = std::move(other.name_);
  }
  return *this;
}

void ComputePipeline::destroy() {
  if (context_ && pipeline_) vkDestroyPipeline(context_->device(), pipeline_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
}

void ComputePipeline::bind(VkCommandBuffer cmd) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
}

void ComputePipeline::push_constants(VkCommandBuffer cmd, const void* data, uint32_t size) const {
  push(cmd, layout_, name_, data, size);
}

// ---------------------------------------------------------------------------------------------
// GraphicsPipeline

GraphicsPipeline::GraphicsPipeline(Context& context, const GraphicsPipelineDesc& desc)
    : context_(&context),
      layout_(context, desc.layout, desc.name),
      depth_bias_(desc.depth_bias),
      depth_bias_constant_(desc.depth_bias_constant),
      depth_bias_slope_(desc.depth_bias_slope),
      name_(desc.name) {
  if (desc.vertex.empty()) {
    throw Error("graphics pipeline \"" + name_ + "\": a vertex shader is required");
  }
  if (desc.conservative_rasterization && !context.features().conservative_rasterization) {
    throw Error("graphics pipeline \"" + name_ + "\": conservative rasterization requested, but " +
                context.device_name() +
                " lacks VK_EXT_conservative_rasterization; check "
                "Context::features().conservative_rasterization and fall back");
  }
  if (!desc.geometry.empty() && !context.features().geometry_shader) {
    throw Error("graphics pipeline \"" + name_ + "\": " + context.device_name() +
                " has no geometry shaders");
  }
  if (!desc.blend.empty() && desc.blend.size() != desc.color_formats.size()) {
    throw Error("graphics pipeline \"" + name_ + "\": " + std::to_string(desc.blend.size()) +
                " blend states for " + std::to_string(desc.color_formats.size()) +
                " color attachments; expected one per attachment or none");
  }

  ModuleList modules{context.device(), {}};
  std::vector<VkPipelineShaderStageCreateInfo> stages;
  auto add_stage = [&](const std::vector<uint32_t>& code, VkShaderStageFlagBits stage) {
    if (code.empty()) return;
    modules.modules.push_back(create_shader_module(context, code, name_));
    VkPipelineShaderStageCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    info.stage = stage;
    info.module = modules.modules.back();
    info.pName = "main";
    stages.push_back(info);
  };
  add_stage(desc.vertex, VK_SHADER_STAGE_VERTEX_BIT);
  add_stage(desc.geometry, VK_SHADER_STAGE_GEOMETRY_BIT);
  add_stage(desc.fragment, VK_SHADER_STAGE_FRAGMENT_BIT);

  VkPipelineVertexInputStateCreateInfo vertex_input{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertex_input.vertexBindingDescriptionCount = static_cast<uint32_t>(desc.vertex_bindings.size());
  vertex_input.pVertexBindingDescriptions = desc.vertex_bindings.data();
  vertex_input.vertexAttributeDescriptionCount =
      static_cast<uint32_t>(desc.vertex_attributes.size());
  vertex_input.pVertexAttributeDescriptions = desc.vertex_attributes.data();

  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;

  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;

  VkPipelineRasterizationConservativeStateCreateInfoEXT conservative{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_CONSERVATIVE_STATE_CREATE_INFO_EXT};
  conservative.conservativeRasterizationMode = VK_CONSERVATIVE_RASTERIZATION_MODE_OVERESTIMATE_EXT;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  if (desc.conservative_rasterization) raster.pNext = &conservative;
  raster.depthClampEnable = desc.depth_clamp;
  raster.polygonMode = desc.polygon;
  raster.cullMode = desc.cull;
  raster.frontFace = desc.front_face;
  raster.depthBiasEnable = desc.depth_bias;
  raster.lineWidth = 1.0f;

  VkPipelineMultisampleStateCreateInfo multisample{
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;

  VkPipelineDepthStencilStateCreateInfo depth{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = desc.depth_test;
  depth.depthWriteEnable = desc.depth_write;
  depth.depthCompareOp = desc.depth_compare;

  std::vector<VkPipelineColorBlendAttachmentState> blend = desc.blend;
  if (blend.empty()) {
    VkPipelineColorBlendAttachmentState write_all{};
    write_all.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                               VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    blend.assign(desc.color_formats.size(), write_all);
  }
  VkPipelineColorBlendStateCreateInfo color_blend{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  color_blend.attachmentCount = static_cast<uint32_t>(blend.size());
  color_blend.pAttachments = blend.data();

  std::vector<VkDynamicState> dynamic{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  if (desc.depth_bias) dynamic.push_back(VK_DYNAMIC_STATE_DEPTH_BIAS);
  VkPipelineDynamicStateCreateInfo dynamic_state{
      VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic_state.dynamicStateCount = static_cast<uint32_t>(dynamic.size());
  dynamic_state.pDynamicStates = dynamic.data();

  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.viewMask = desc.view_mask;
  rendering.colorAttachmentCount = static_cast<uint32_t>(desc.color_formats.size());
  rendering.pColorAttachmentFormats = desc.color_formats.data();
  rendering.depthAttachmentFormat = desc.depth_format;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = static_cast<uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &color_blend;
  info.pDynamicState = &dynamic_state;
  info.layout = layout_.handle();
  check(vkCreateGraphicsPipelines(context.device(), context.pipeline_cache(), 1, &info, nullptr,
                                  &pipeline_),
        ("vkCreateGraphicsPipelines for \"" + name_ + "\"").c_str());
  context.set_debug_name(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<uint64_t>(pipeline_), name_);
}

GraphicsPipeline::~GraphicsPipeline() {
  destroy();
}

GraphicsPipeline::GraphicsPipeline(GraphicsPipeline&& other) noexcept
    : context_(other.context_),
      layout_(std::move(other.layout_)),
      pipeline_(std::exchange(other.pipeline_, VK_NULL_HANDLE)),
      depth_bias_(other.depth_bias_),
      depth_bias_constant_(other.depth_bias_constant_),
      depth_bias_slope_(other.depth_bias_slope_),
      name_(std::move(other.name_)) {}

GraphicsPipeline& GraphicsPipeline::operator=(GraphicsPipeline&& other) noexcept {
  if (this != &other) {
    destroy();
    context_ = other.context_;
    layout_ = std::move(other.layout_);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
    depth_bias_ = other.depth_bias_;
    depth_bias_constant_ = other.depth_bias_constant_;
    depth_bias_slope_ = other.depth_bias_slope_;
    name_ = std::move(other.name_);
  }
  return *this;
}

void GraphicsPipeline::destroy() {
  if (context_ && pipeline_) vkDestroyPipeline(context_->device(), pipeline_, nullptr);
  pipeline_ = VK_NULL_HANDLE;
}

void GraphicsPipeline::bind(VkCommandBuffer cmd) const {
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
  if (depth_bias_) vkCmdSetDepthBias(cmd, depth_bias_constant_, 0.0f, depth_bias_slope_);
}

void GraphicsPipeline::push_constants(VkCommandBuffer cmd, const void* data, uint32_t size) const {
  push(cmd, layout_, name_, data, size);
}

void GraphicsPipeline::set_viewport(VkCommandBuffer cmd, uint32_t width, uint32_t height) {
  VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
  VkRect2D scissor{{0, 0}, {width, height}};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

// ---------------------------------------------------------------------------------------------
// DescriptorWriter

DescriptorWriter& DescriptorWriter::buffer(uint32_t binding, VkDescriptorType type, VkBuffer handle,
                                           VkDeviceSize offset, VkDeviceSize range) {
  writes_.push_back({binding, type, buffers_.size(), 1, true});
  buffers_.push_back({handle, offset, range});
  return *this;
}

DescriptorWriter& DescriptorWriter::storage_buffer(uint32_t binding, const Buffer& target,
                                                   VkDeviceSize offset, VkDeviceSize range) {
  return buffer(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, target.handle(), offset, range);
}

DescriptorWriter& DescriptorWriter::uniform_buffer(uint32_t binding, const Buffer& target,
                                                   VkDeviceSize offset, VkDeviceSize range) {
  return buffer(binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, target.handle(), offset, range);
}

DescriptorWriter& DescriptorWriter::sampled_image(uint32_t binding, VkImageView view,
                                                  VkImageLayout layout, VkSampler sampler) {
  writes_.push_back({binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, images_.size(), 1, false});
  images_.push_back({sampler, view, layout});
  return *this;
}

DescriptorWriter& DescriptorWriter::storage_image(uint32_t binding, VkImageView view,
                                                  VkImageLayout layout) {
  writes_.push_back({binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, images_.size(), 1, false});
  images_.push_back({VK_NULL_HANDLE, view, layout});
  return *this;
}

DescriptorWriter& DescriptorWriter::image_array(uint32_t binding,
                                                std::vector<VkDescriptorImageInfo> images) {
  if (images.empty()) return *this;
  writes_.push_back({binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, images_.size(),
                     static_cast<uint32_t>(images.size()), false});
  images_.insert(images_.end(), images.begin(), images.end());
  return *this;
}

void DescriptorWriter::push(VkCommandBuffer cmd, VkPipelineBindPoint bind_point,
                            VkPipelineLayout layout, uint32_t set) {
  if (writes_.empty()) return;
  // Pointers are taken only now: the vectors may have reallocated while collecting.
  std::vector<VkWriteDescriptorSet> writes;
  writes.reserve(writes_.size());
  for (const Pending& pending : writes_) {
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstBinding = pending.binding;
    write.descriptorCount = pending.count;
    write.descriptorType = pending.type;
    if (pending.is_buffer) {
      write.pBufferInfo = &buffers_[pending.first];
    } else {
      write.pImageInfo = &images_[pending.first];
    }
    writes.push_back(write);
  }
  push_descriptor_set_function()(cmd, bind_point, layout, set, static_cast<uint32_t>(writes.size()),
                                 writes.data());
}

void DescriptorWriter::clear() {
  writes_.clear();
  buffers_.clear();
  images_.clear();
}

}  // namespace voxgi::gpu
