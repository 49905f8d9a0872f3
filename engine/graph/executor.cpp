#include "engine/graph/executor.hpp"

#include <glm/gtc/packing.hpp>

#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"
#include "engine/gpu/image.hpp"
#include "engine/gpu/timestamps.hpp"
#include "engine/graph/memory_budget.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::graph {

namespace {

constexpr VkAccessFlags2 kAnyAccess = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;

// What a pass writes has a new version once it executed.
void advance_versions(const CompiledPass& pass, std::vector<uint64_t>& versions) {
  for (const SlotBinding& b : pass.bindings) {
    if (!b.is_input && b.resource >= 0) ++versions[static_cast<size_t>(b.resource)];
  }
}

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

// One texel of `format` at `p` as RGBA32F (missing channels: 0, alpha 1).
glm::vec4 decode_texel(VkFormat format, const uint8_t* p) {
  auto u8 = [&](int i) { return static_cast<float>(p[i]) / 255.0f; };
  auto u16 = [&](int i) {
    uint16_t v;
    std::memcpy(&v, p + 2 * i, 2);
    return v;
  };
  auto f32 = [&](int i) {
    float v;
    std::memcpy(&v, p + 4 * i, 4);
    return v;
  };
  auto u32 = [&](int i) {
    uint32_t v;
    std::memcpy(&v, p + 4 * i, 4);
    return v;
  };
  auto half = [&](int i) { return glm::unpackHalf1x16(u16(i)); };
  switch (format) {
    case VK_FORMAT_R8_UNORM:
      return {u8(0), 0, 0, 1};
    case VK_FORMAT_R8G8_UNORM:
      return {u8(0), u8(1), 0, 1};
    case VK_FORMAT_R8G8B8A8_UNORM:
      return {u8(0), u8(1), u8(2), u8(3)};
    case VK_FORMAT_R8G8B8A8_SRGB:
      return {srgb_to_linear(u8(0)), srgb_to_linear(u8(1)), srgb_to_linear(u8(2)), u8(3)};
    case VK_FORMAT_R16G16B16A16_UNORM:
      return glm::vec4(u16(0), u16(1), u16(2), u16(3)) / 65535.0f;
    case VK_FORMAT_R16_SFLOAT:
      return {half(0), 0, 0, 1};
    case VK_FORMAT_R16G16_SFLOAT:
      return {half(0), half(1), 0, 1};
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      return {half(0), half(1), half(2), half(3)};
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT:
      return {f32(0), 0, 0, 1};
    case VK_FORMAT_R32G32_SFLOAT:
      return {f32(0), f32(1), 0, 1};
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return {f32(0), f32(1), f32(2), f32(3)};
    case VK_FORMAT_R32_UINT:
      return {static_cast<float>(u32(0)), 0, 0, 1};
    case VK_FORMAT_R32_SINT:
      return {static_cast<float>(static_cast<int32_t>(u32(0))), 0, 0, 1};
    case VK_FORMAT_R32G32_UINT:
      return {static_cast<float>(u32(0)), static_cast<float>(u32(1)), 0, 1};
    case VK_FORMAT_R32G32B32A32_UINT:
      return {static_cast<float>(u32(0)), static_cast<float>(u32(1)), static_cast<float>(u32(2)),
              static_cast<float>(u32(3))};
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
      return {glm::unpackF2x11_1x10(u32(0)), 1.0f};
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32: {
      const uint32_t v = u32(0);
      return {static_cast<float>(v & 0x3ff) / 1023.0f,
              static_cast<float>((v >> 10) & 0x3ff) / 1023.0f,
              static_cast<float>((v >> 20) & 0x3ff) / 1023.0f, static_cast<float>(v >> 30) / 3.0f};
    }
    case VK_FORMAT_D16_UNORM:
      return {static_cast<float>(u16(0)) / 65535.0f, 0, 0, 1};
    default:
      throw std::invalid_argument("read_output: unsupported format " + format_name(format));
  }
}

}  // namespace

Executor::Executor(gpu::Context& context, gpu::ShaderCompiler& shaders, const Registry& registry)
    : context_(context), shaders_(shaders), registry_(registry) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = context_.command_pool();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  gpu::check(vkAllocateCommandBuffers(context_.device(), &alloc, &cmd_),
             "vkAllocateCommandBuffers");
  VkFenceCreateInfo fence{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  gpu::check(vkCreateFence(context_.device(), &fence, nullptr, &fence_), "vkCreateFence");
  uniforms_ = std::make_unique<gpu::Buffer>(context_, sizeof(FrameUniforms),
                                            VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                            gpu::MemoryUsage::CpuToGpu, "frame.uniforms");
}

Executor::~Executor() {
  context_.wait_idle();
  release();
  vkDestroyFence(context_.device(), fence_, nullptr);
  vkFreeCommandBuffers(context_.device(), context_.command_pool(), 1, &cmd_);
}

void Executor::release() {
  passes_.clear();  // passes may hold pipelines; they go before the resources they used
  physical_.clear();
  shared_memory_.clear();
}

void Executor::bind_memory_blocks() {
  for (const MemoryBlock& block : graph_.memory_blocks) {
    // Members whose memory types intersect share one allocation; a member that fits none of
    // the allocations made so far starts another (devices may keep some formats apart).
    std::vector<VkMemoryRequirements> combined;
    std::vector<std::vector<size_t>> members;
    for (int p : block.physical) {
      const Physical& phys = physical_[static_cast<size_t>(p)];
      const VkMemoryRequirements need =
          phys.image ? phys.image->memory_requirements() : phys.buffer->memory_requirements();
      size_t g = 0;
      while (g < combined.size() && (combined[g].memoryTypeBits & need.memoryTypeBits) == 0) ++g;
      if (g == combined.size()) {
        combined.push_back(need);
        members.emplace_back();
      } else {
        combined[g].size = std::max(combined[g].size, need.size);
        combined[g].alignment = std::max(combined[g].alignment, need.alignment);
        combined[g].memoryTypeBits &= need.memoryTypeBits;
      }
      members[g].push_back(static_cast<size_t>(p));
    }
    for (size_t g = 0; g < combined.size(); ++g) {
      shared_memory_.push_back(
          std::make_unique<gpu::SharedMemory>(context_.allocator(), combined[g]));
      for (size_t p : members[g]) {
        Physical& phys = physical_[p];
        const gpu::Allocation& memory = shared_memory_.back()->allocation();
        if (phys.image) {
          phys.image->bind_memory(memory);
        } else {
          phys.buffer->bind_memory(memory);
        }
      }
    }
  }
}

void Executor::build(const CompiledGraph& graph, const scene::Scene& scene,
                     scene::GpuScene& gpu_scene) {
  // Before anything is released or allocated: a graph too large for the device is refused
  // and the current one keeps running.
  check_memory_budget(graph, device_memory_budget(context_.physical_device()));
  // `when` conditions on device features are decided when compiling; they must have been
  // decided for this device, or the graph would run passes the device cannot.
  if (!graph.device_conditions.empty() &&
      (!graph.device_queried ||
       graph.device_features != gpu::device_feature_values(context_.features()))) {
    throw std::invalid_argument(
        "graph '" + graph.file + "': the `when` of pass '" + graph.device_conditions[0].pass +
        "' reads device features, but the graph was compiled " +
        (graph.device_queried ? "for another device ('" + graph.device_name + "')"
                              : std::string("without a device")) +
        "; compile it for '" + context_.device_name() + "' (graph::use_device)");
  }
  context_.wait_idle();
  // Persistent contents survive a rebuild when their description and usage still fit.
  struct Kept {
    ResourceInfo info;
    VkImageUsageFlags image_usage;
    VkBufferUsageFlags buffer_usage;
    Physical physical;
    std::vector<ResourceState> end_state;
  };
  std::map<std::string, Kept> kept;
  for (size_t p = 0; p < physical_.size(); ++p) {
    const PhysicalResource& old = graph_.physical[p];
    if (old.resources.size() != 1) continue;
    const CompiledResource& r = graph_.resources[static_cast<size_t>(old.resources[0])];
    if (!r.info.persistent) continue;
    kept.emplace(r.info.name, Kept{r.info, old.image_usage, old.buffer_usage,
                                   std::move(physical_[p]), r.end_state});
  }
  passes_.clear();
  physical_.clear();
  shared_memory_.clear();

  graph_ = graph;
  sync_ = std::make_unique<FrameSync>(graph_);
  frame_barriers_ = {};
  scene_ = &scene;
  gpu_scene_ = &gpu_scene;
  scene::SceneFeatures features = scene.features();
  scene_min_ = features.bounds_min;
  scene_max_ = features.bounds_max;
  light_count_ = static_cast<float>(features.light_count);

  physical_.resize(graph_.physical.size());
  for (size_t p = 0; p < graph_.physical.size(); ++p) {
    const PhysicalResource& desc = graph_.physical[p];
    const CompiledResource& first = graph_.resources[static_cast<size_t>(desc.resources[0])];
    Physical& phys = physical_[p];
    auto it = kept.find(first.info.name);
    if (it != kept.end() && desc.resources.size() == 1 && first.info.persistent &&
        same_description(it->second.info, first.info) &&
        (desc.image_usage & ~it->second.image_usage) == 0 &&
        (desc.buffer_usage & ~it->second.buffer_usage) == 0) {
      phys = std::move(it->second.physical);
      phys.fresh = false;
      phys.kept_layouts.clear();
      for (const ResourceState& s : it->second.end_state) phys.kept_layouts.push_back(s.layout);
      continue;
    }
    std::string name = first.info.name;
    for (size_t i = 1; i < desc.resources.size(); ++i) {
      name += "+" + graph_.resources[static_cast<size_t>(desc.resources[i])].info.name;
    }
    const bool aliased = desc.memory_block >= 0;
    if (desc.info.kind == ResourceKind::Buffer) {
      phys.buffer =
          aliased
              ? std::make_unique<gpu::Buffer>(context_, desc.info.buffer_size, desc.buffer_usage,
                                              name, gpu::BindLater{})
              : std::make_unique<gpu::Buffer>(context_, desc.info.buffer_size, desc.buffer_usage,
                                              gpu::MemoryUsage::GpuOnly, name);
    } else {
      gpu::ImageDesc image;
      image.type = desc.info.kind == ResourceKind::Image2D ? VK_IMAGE_TYPE_2D : VK_IMAGE_TYPE_3D;
      image.format = desc.info.format;
      image.extent = desc.info.extent;
      image.mip_levels = desc.info.mip_levels;
      image.array_layers = desc.info.array_layers;
      image.usage = desc.image_usage;
      image.name = name;
      phys.image = aliased ? std::make_unique<gpu::Image>(context_, image, gpu::BindLater{})
                           : std::make_unique<gpu::Image>(context_, image);
    }
    phys.fresh = true;
  }
  bind_memory_blocks();
  kept.clear();  // persistent resources the new graph does not keep are freed here

  const uint32_t queries = static_cast<uint32_t>(2 * graph_.passes.size() + 2);
  timestamps_ = std::make_unique<gpu::TimestampQueries>(context_, queries);

  frame_ = FrameInfo{};
  frame_.width = graph_.viewport_width;
  frame_.height = graph_.viewport_height;
  frame_.uniform_buffer = uniforms_.get();
  first_frame_ = true;
  rendered_ = false;
  timings_.clear();

  resource_versions_.assign(graph_.resources.size(), 0);
  for (size_t r = 0; r < graph_.resources.size(); ++r) {
    const auto known = versions_by_name_.find(graph_.resources[r].info.name);
    if (known != versions_by_name_.end()) resource_versions_[r] = known->second;
  }
  for (const CompiledPass& pass : graph_.passes) {
    LivePass live;
    live.pass = registry_.create(pass.type);
    live.impl = std::make_unique<PassContextImpl>();
    PassContextImpl& impl = *live.impl;
    impl.gpu = &context_;
    impl.shaders = &shaders_;
    impl.scene = scene_;
    impl.gpu_scene = gpu_scene_;
    impl.frame = &frame_;
    impl.pass = &pass;
    impl.resource_versions = &resource_versions_;
    for (const SlotBinding& b : pass.bindings) {
      BoundResource bound;
      bound.info = &b.info;
      bound.layout = b.state.layout;
      if (b.resource >= 0) {
        const int p = graph_.resources[static_cast<size_t>(b.resource)].physical;
        Physical& phys = physical_[static_cast<size_t>(p)];
        bound.image = phys.image.get();
        bound.buffer = phys.buffer.get();
        if (phys.image) {
          bound.view = b.info.mip < 0 ? phys.image->view()
                                      : phys.image->view(static_cast<uint32_t>(b.info.mip));
        }
      }
      impl.bound.push_back(bound);
    }
    passes_.push_back(std::move(live));
    run_setup(passes_.back());
  }
}

void Executor::run_setup(LivePass& live) {
  PassContext ctx(*live.impl);
  try {
    live.pass->setup(ctx);
  } catch (const std::exception& e) {
    throw std::runtime_error("pass '" + live.impl->pass->name + "' (" + live.impl->pass->type +
                             ") setup failed: " + e.what());
  }
  live.impl->params_changed = true;
}

void Executor::fill_frame(const FrameInput& input) {
  FrameUniforms& u = frame_.uniforms;
  const CameraView& camera = input.camera;
  u.view = camera.view;
  u.proj = camera.proj;
  u.view_proj = camera.proj * camera.view;
  u.inv_view = glm::inverse(camera.view);
  u.inv_proj = glm::inverse(camera.proj);
  u.inv_view_proj = glm::inverse(u.view_proj);
  u.camera_position = glm::vec4(camera.position, 1.0f);
  const float w = static_cast<float>(std::max(1u, graph_.viewport_width));
  const float h = static_cast<float>(std::max(1u, graph_.viewport_height));
  u.viewport = glm::vec4(w, h, 1.0f / w, 1.0f / h);
  u.clip = glm::vec4(camera.znear, camera.zfar, static_cast<float>(input.time),
                     static_cast<float>(frame_.index));
  u.scene_min = glm::vec4(scene_min_, light_count_);
  u.scene_max = glm::vec4(scene_max_, 0.0f);
  uniforms_->upload(&u, sizeof(u));
  frame_.time = input.time;
  frame_.first_frame = first_frame_;
  frame_.camera_changed = first_frame_ || input.camera_changed;
  frame_.lights_changed = first_frame_ || input.lights_changed;
  frame_.geometry_changed = first_frame_ || input.geometry_changed;
}

void Executor::record_barriers(VkCommandBuffer cmd, const std::vector<Barrier>& barriers) {
  std::vector<VkMemoryBarrier2> memory;
  std::vector<VkImageMemoryBarrier2> images;
  std::vector<VkBufferMemoryBarrier2> buffers;
  for (const Barrier& b : barriers) {
    if (b.is_global) {
      VkMemoryBarrier2 m{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
      m.srcStageMask = b.src_stages;
      m.srcAccessMask = b.src_access;
      m.dstStageMask = b.dst_stages;
      m.dstAccessMask = b.dst_access;
      memory.push_back(m);
      continue;
    }
    const CompiledResource& r = graph_.resources[static_cast<size_t>(b.resource)];
    Physical& phys = physical_[static_cast<size_t>(r.physical)];
    if (b.is_buffer) {
      VkBufferMemoryBarrier2 m{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
      m.srcStageMask = b.src_stages;
      m.srcAccessMask = b.src_access;
      m.dstStageMask = b.dst_stages;
      m.dstAccessMask = b.dst_access;
      m.srcQueueFamilyIndex = m.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      m.buffer = phys.buffer->handle();
      m.size = VK_WHOLE_SIZE;
      buffers.push_back(m);
    } else {
      VkImageMemoryBarrier2 m{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
      m.srcStageMask = b.src_stages;
      m.srcAccessMask = b.src_access;
      m.dstStageMask = b.dst_stages;
      m.dstAccessMask = b.dst_access;
      m.oldLayout = b.old_layout;
      m.newLayout = b.new_layout;
      m.srcQueueFamilyIndex = m.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      m.image = phys.image->handle();
      m.subresourceRange = {phys.image->aspect(), b.base_mip, b.mip_count, 0, r.info.array_layers};
      images.push_back(m);
    }
  }
  if (memory.empty() && images.empty() && buffers.empty()) return;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = static_cast<uint32_t>(memory.size());
  dependency.pMemoryBarriers = memory.data();
  dependency.imageMemoryBarrierCount = static_cast<uint32_t>(images.size());
  dependency.pImageMemoryBarriers = images.data();
  dependency.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers.size());
  dependency.pBufferMemoryBarriers = buffers.data();
  vkCmdPipelineBarrier2(cmd, &dependency);
}

// New images start in the layouts the frame expects at its start (carried ones cleared to
// zero first); kept persistent images move from the old graph's end layouts to the new ones.
void Executor::record_initialisation(VkCommandBuffer cmd) {
  for (size_t p = 0; p < physical_.size(); ++p) {
    Physical& phys = physical_[p];
    const PhysicalResource& desc = graph_.physical[p];
    const CompiledResource& r = graph_.resources[static_cast<size_t>(desc.resources.back())];
    if (phys.buffer) {
      if (!phys.fresh || !desc.carries_contents) continue;
      vkCmdFillBuffer(cmd, phys.buffer->handle(), 0, VK_WHOLE_SIZE, 0);
      Barrier b;
      b.resource = desc.resources.back();
      b.is_buffer = true;
      b.src_stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
      b.src_access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
      b.dst_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
      b.dst_access = kAnyAccess;
      record_barriers(cmd, {b});
      continue;
    }
    std::vector<VkImageLayout> from(desc.info.mip_levels, VK_IMAGE_LAYOUT_UNDEFINED);
    if (!phys.fresh) {
      from = phys.kept_layouts;
    } else if (desc.carries_contents) {
      Barrier to_dst;
      to_dst.resource = desc.resources.back();
      to_dst.mip_count = desc.info.mip_levels;
      to_dst.dst_stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
      to_dst.dst_access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
      to_dst.new_layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
      record_barriers(cmd, {to_dst});
      const VkImageSubresourceRange range = phys.image->range();
      if (is_depth_format(desc.info.format)) {
        const VkClearDepthStencilValue zero{0.0f, 0};
        vkCmdClearDepthStencilImage(cmd, phys.image->handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                    &zero, 1, &range);
      } else {
        const VkClearColorValue zero{};
        vkCmdClearColorImage(cmd, phys.image->handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero,
                             1, &range);
      }
      from.assign(desc.info.mip_levels, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    }
    std::vector<Barrier> moves;
    for (uint32_t m = 0; m < desc.info.mip_levels && m < r.end_state.size(); ++m) {
      const VkImageLayout to = r.end_state[m].layout;
      if (to == VK_IMAGE_LAYOUT_UNDEFINED || (to == from[m] && !phys.fresh)) continue;
      Barrier b;
      b.resource = desc.resources.back();
      b.base_mip = m;
      b.src_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
      b.src_access = kAnyAccess;
      b.dst_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
      b.dst_access = kAnyAccess;
      b.old_layout = from[m];
      b.new_layout = to;
      moves.push_back(b);
    }
    record_barriers(cmd, moves);
  }
}

// Frame history: each "@previous" twin becomes a copy of the current version, whole.
void Executor::record_history_copies(VkCommandBuffer cmd) {
  for (const HistoryCopy& copy : graph_.history_copies) {
    const CompiledResource& from = graph_.resources[static_cast<size_t>(copy.from)];
    const CompiledResource& to = graph_.resources[static_cast<size_t>(copy.to)];
    Physical& src = physical_[static_cast<size_t>(from.physical)];
    Physical& dst = physical_[static_cast<size_t>(to.physical)];
    if (src.buffer) {
      const VkBufferCopy region{0, 0, from.info.buffer_size};
      vkCmdCopyBuffer(cmd, src.buffer->handle(), dst.buffer->handle(), 1, &region);
    } else {
      std::vector<VkImageCopy> regions;
      const VkExtent3D extent = src.image->extent();
      for (uint32_t m = 0; m < from.info.mip_levels; ++m) {
        VkImageCopy region{};
        region.srcSubresource = {src.image->aspect(), m, 0, from.info.array_layers};
        region.dstSubresource = region.srcSubresource;
        region.extent = {std::max(1u, extent.width >> m), std::max(1u, extent.height >> m),
                         std::max(1u, extent.depth >> m)};
        regions.push_back(region);
      }
      vkCmdCopyImage(cmd, src.image->handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     dst.image->handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                     static_cast<uint32_t>(regions.size()), regions.data());
    }
    resource_versions_[static_cast<size_t>(copy.to)] =
        resource_versions_[static_cast<size_t>(copy.from)];
  }
}

// Asked before anything is recorded, so that the frame's barriers can leave out what skipped
// passes would have written. Each pass sees the versions the passes before it leave, counted
// on a copy; execute() counts them for real.
std::vector<std::string> Executor::skip_reasons() {
  std::vector<std::string> reasons(passes_.size());
  std::vector<uint64_t> versions = resource_versions_;
  for (size_t s = 0; s < passes_.size(); ++s) {
    LivePass& live = passes_[s];
    const CompiledPass& pass = graph_.passes[s];
    live.impl->resource_versions = &versions;
    PassContext ctx(*live.impl);
    reasons[s] = live.pass->skip_reason(ctx);
    live.impl->resource_versions = &resource_versions_;
    if (reasons[s].empty()) {
      advance_versions(pass, versions);
      continue;
    }
    const std::string what =
        "pass '" + pass.name + "' (" + pass.type + ") reported a skip (\"" + reasons[s] + "\"), ";
    if (!pass.type_info->may_skip) {
      throw std::logic_error(what + "but its type does not declare may_skip");
    }
    for (const SlotBinding& b : pass.bindings) {
      if (!skip_leaves_undefined(b)) continue;
      throw std::logic_error(what + "but it writes the transient resource '" + b.info.name +
                             "' (slot '" + b.slot +
                             "'), which would be left undefined; a pass may skip only when "
                             "everything it writes is persistent");
    }
  }
  return reasons;
}

void Executor::render(const FrameInput& input) {
  if (!scene_) throw std::logic_error("Executor::render() called before build()");
  fill_frame(input);
  const std::vector<std::string> skips = skip_reasons();
  std::vector<bool> skipped(skips.size());
  for (size_t s = 0; s < skips.size(); ++s) skipped[s] = !skips[s].empty();
  // A frame that fails to record is not submitted: the tracked state goes back to before it.
  const FrameSync sync_before = *sync_;
  FrameBarriers barriers = sync_->plan(skipped);
  gpu::check(vkResetCommandBuffer(cmd_, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  gpu::check(vkBeginCommandBuffer(cmd_, &begin), "vkBeginCommandBuffer");
  std::vector<PassTiming> timings;
  std::vector<std::pair<uint32_t, uint32_t>> queries;
  uint32_t frame_begin_query = 0;
  uint32_t frame_end_query = 0;
  try {
    timestamps_->reset(cmd_);
    frame_begin_query = timestamps_->write(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
    if (first_frame_) record_initialisation(cmd_);
    record_barriers(cmd_, barriers.frame_start);
    for (size_t s = 0; s < passes_.size(); ++s) {
      LivePass& live = passes_[s];
      const CompiledPass& pass = graph_.passes[s];
      record_barriers(cmd_, barriers.passes[s]);
      PassTiming timing{pass.name, pass.type, 0.0, 0.0, skips[s]};
      PassContext ctx(*live.impl);
      // A label per pass, so that capture tools show the graph's pass names.
      context_.begin_label(cmd_, pass.name + " (" + pass.type + ")");
      const uint32_t begin_query = timestamps_->write(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      if (timing.skipped.empty()) {
        live.impl->cmd = cmd_;
        live.impl->executing = true;
        const auto start = std::chrono::steady_clock::now();
        try {
          live.pass->execute(ctx);
        } catch (const std::exception& e) {
          live.impl->executing = false;
          throw std::runtime_error("pass '" + pass.name + "' (" + pass.type +
                                   ") failed: " + e.what());
        }
        timing.cpu_ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        live.impl->executing = false;
        live.impl->params_changed = false;
        advance_versions(pass, resource_versions_);
        for (const SlotBinding& b : pass.bindings) {
          if (b.is_input || b.resource < 0) continue;
          const size_t r = static_cast<size_t>(b.resource);
          versions_by_name_[graph_.resources[r].info.name] = resource_versions_[r];
        }
      }
      const uint32_t end_query = timestamps_->write(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
      context_.end_label(cmd_);
      queries.emplace_back(begin_query, end_query);
      timings.push_back(std::move(timing));
    }
    record_barriers(cmd_, barriers.history);
    record_history_copies(cmd_);
    record_barriers(cmd_, barriers.frame_end);
    frame_end_query = timestamps_->write(cmd_, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT);
  } catch (...) {
    vkEndCommandBuffer(cmd_);
    *sync_ = sync_before;
    throw;
  }
  gpu::check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");

  VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmd_info.commandBuffer = cmd_;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmd_info;
  gpu::check(vkResetFences(context_.device(), 1, &fence_), "vkResetFences");
  context_.submit(submit, fence_);
  gpu::check(vkWaitForFences(context_.device(), 1, &fence_, VK_TRUE, UINT64_MAX),
             "vkWaitForFences");

  if (timestamps_->supported() && timestamps_->count() > 0) {
    const std::vector<uint64_t> values = timestamps_->read();
    for (size_t s = 0; s < timings.size(); ++s) {
      const auto [b, e] = queries[s];
      if (b < values.size() && e < values.size())
        timings[s].gpu_ms = timestamps_->milliseconds(values[b], values[e]);
    }
    frame_gpu_ms_ =
        frame_begin_query < values.size() && frame_end_query < values.size()
            ? timestamps_->milliseconds(values[frame_begin_query], values[frame_end_query])
            : 0.0;
  }
  timings_ = std::move(timings);
  frame_barriers_ = std::move(barriers);
  for (Physical& phys : physical_) phys.fresh = false;
  first_frame_ = false;
  rendered_ = true;
  ++frame_.index;
}

std::vector<float> Executor::read_output(const std::string& output, uint32_t& width,
                                         uint32_t& height) {
  auto it = graph_.outputs.find(output);
  if (it == graph_.outputs.end()) {
    std::string names;
    for (const auto& [name, r] : graph_.outputs) names += (names.empty() ? "" : ", ") + name;
    throw std::invalid_argument("graph '" + graph_.name + "' has no output '" + output +
                                "' (it has " + names + ")");
  }
  if (!rendered_) throw std::logic_error("read_output('" + output + "') before any render()");
  const CompiledResource& r = graph_.resources[static_cast<size_t>(it->second)];
  Physical& phys = physical_[static_cast<size_t>(r.physical)];
  if (!phys.image) {
    throw std::invalid_argument("output '" + output + "' is the buffer '" + r.info.name +
                                "', not an image");
  }
  const std::vector<uint8_t> bytes = phys.image->download(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  width = r.info.extent.width;
  height = r.info.extent.height;
  const uint32_t texel = format_texel_bytes(r.info.format);
  const size_t count = bytes.size() / texel;
  std::vector<float> rgba(count * 4);
  for (size_t i = 0; i < count; ++i) {
    const glm::vec4 v = decode_texel(r.info.format, bytes.data() + i * texel);
    for (int c = 0; c < 4; ++c) rgba[i * 4 + static_cast<size_t>(c)] = v[c];
  }
  return rgba;
}

bool Executor::set_param(const std::string& key, const std::string& value) {
  std::vector<std::string> candidates;
  for (size_t s = 0; s < graph_.passes.size(); ++s) {
    CompiledPass& pass = graph_.passes[s];
    for (const ParamSpec& spec : pass.type_info->params) {
      candidates.push_back(pass.name + "." + spec.name);
      if (key != pass.name + "." + spec.name) continue;
      if (spec.sizes_outputs) {
        throw ParamNeedsRecompile("parameter '" + key +
                                  "' sizes the pass's outputs: compile the graph again with it");
      }
      const ParamValue previous = pass.params[spec.name];
      pass.params[spec.name] = parse_param_value(spec, key, value);
      if (std::vector<Diagnostic> problems = validate_pass(pass); !problems.empty()) {
        pass.params[spec.name] = previous;
        throw GraphError(std::move(problems));
      }
      LivePass& live = passes_[s];
      live.impl->params_changed = true;
      if (spec.live) return true;
      context_.wait_idle();
      run_setup(live);
      return false;
    }
  }
  for (const CulledPass& c : graph_.culled) {
    if (key.rfind(c.name + ".", 0) == 0) {
      Diagnostic d = message_only("pass '" + c.name + "' was culled (" + c.reason +
                                  "), so its parameters cannot change");
      d.field = key;
      throw GraphError(std::move(d));
    }
  }
  Diagnostic d = message_only("unknown parameter key '" + key + "' (expected 'pass.parameter')",
                              did_you_mean(key, candidates));
  d.field = key;
  throw GraphError(std::move(d));
}

gpu::Image* Executor::image(const std::string& resource) {
  const int r = graph_.find_resource(resource);
  if (r < 0 || graph_.resources[static_cast<size_t>(r)].physical < 0) return nullptr;
  return physical_[static_cast<size_t>(graph_.resources[static_cast<size_t>(r)].physical)]
      .image.get();
}

gpu::Buffer* Executor::buffer(const std::string& resource) {
  const int r = graph_.find_resource(resource);
  if (r < 0 || graph_.resources[static_cast<size_t>(r)].physical < 0) return nullptr;
  return physical_[static_cast<size_t>(graph_.resources[static_cast<size_t>(r)].physical)]
      .buffer.get();
}

}  // namespace voxgi::graph
