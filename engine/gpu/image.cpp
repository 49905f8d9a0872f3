#include "engine/gpu/image.hpp"

#include <cstring>
#include <utility>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/context.hpp"
#include "engine/gpu/error.hpp"
#include "engine/gpu/sync.hpp"

namespace voxgi::gpu {

namespace {

constexpr BarrierScope kAnything{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                 VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};
constexpr BarrierScope kTransferWrite{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                      VK_ACCESS_2_TRANSFER_WRITE_BIT};
constexpr BarrierScope kTransferRead{VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                                     VK_ACCESS_2_TRANSFER_READ_BIT};

std::string usage_text(VkImageUsageFlags usage) {
  std::string text;
  auto add = [&](VkImageUsageFlags bit, const char* name) {
    if (!(usage & bit)) return;
    if (!text.empty()) text.push_back('|');
    text.append(name);
  };
  add(VK_IMAGE_USAGE_TRANSFER_SRC_BIT, "TRANSFER_SRC");
  add(VK_IMAGE_USAGE_TRANSFER_DST_BIT, "TRANSFER_DST");
  add(VK_IMAGE_USAGE_SAMPLED_BIT, "SAMPLED");
  add(VK_IMAGE_USAGE_STORAGE_BIT, "STORAGE");
  add(VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, "COLOR_ATTACHMENT");
  add(VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, "DEPTH_STENCIL_ATTACHMENT");
  return text;
}

std::string extent_text(VkExtent3D e) {
  return std::to_string(e.width) + "x" + std::to_string(e.height) + "x" + std::to_string(e.depth);
}

}  // namespace

Image::Image(Context& context, const ImageDesc& desc) : Image(context, desc, BindLater{}) {
  owns_memory_ = true;
  try {
    allocation_ = context.allocator().allocate(memory_requirements(), MemoryUsage::GpuOnly);
    check(vkBindImageMemory(context.device(), image_, allocation_.memory, allocation_.offset),
          "vkBindImageMemory");
  } catch (const Error& error) {
    throw Error("image \"" + desc_.name + "\" (" + extent_text(desc_.extent) + ", " +
                format_name(desc_.format) + "): " + error.what());
  }
}

Image::Image(Context& context, const ImageDesc& desc, BindLater)
    : context_(&context), desc_(desc), owns_memory_(false) {
  const std::string label = "image \"" + desc_.name + "\"";
  if (desc_.extent.width == 0 || desc_.extent.height == 0 || desc_.extent.depth == 0) {
    throw Error(label + ": extent " + extent_text(desc_.extent) +
                " has a zero dimension; expected every dimension >= 1");
  }
  if (desc_.type != VK_IMAGE_TYPE_3D && desc_.extent.depth != 1) {
    throw Error(label + ": a 2D image needs extent.depth == 1, got " +
                std::to_string(desc_.extent.depth));
  }
  if (desc_.type == VK_IMAGE_TYPE_3D && desc_.array_layers != 1) {
    throw Error(label + ": a 3D image needs array_layers == 1");
  }
  if (desc_.array_layers == 0) throw Error(label + ": array_layers must be >= 1");
  uint32_t max_mips = full_mip_count(desc_.extent);
  if (desc_.mip_levels == 0) desc_.mip_levels = max_mips;
  if (desc_.mip_levels > max_mips) {
    throw Error(label + ": " + std::to_string(desc_.mip_levels) + " mip levels requested, " +
                extent_text(desc_.extent) + " has at most " + std::to_string(max_mips));
  }
  desc_.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  aspect_ = aspect_of(desc_.format);

  VkImageFormatProperties limits{};
  VkResult supported = vkGetPhysicalDeviceImageFormatProperties(
      context.physical_device(), desc_.format, desc_.type, VK_IMAGE_TILING_OPTIMAL, desc_.usage,
      desc_.flags, &limits);
  if (supported != VK_SUCCESS) {
    throw Error(label + ": format " + format_name(desc_.format) + " with usage " +
                usage_text(desc_.usage) + " is not supported by " + context.device_name() + " (" +
                to_string(supported) + "); choose another format or usage");
  }
  if (desc_.extent.width > limits.maxExtent.width ||
      desc_.extent.height > limits.maxExtent.height ||
      desc_.extent.depth > limits.maxExtent.depth || desc_.array_layers > limits.maxArrayLayers) {
    throw Error(label + ": extent " + extent_text(desc_.extent) + " x " +
                std::to_string(desc_.array_layers) + " layers exceeds the device limit " +
                extent_text(limits.maxExtent) + " x " + std::to_string(limits.maxArrayLayers));
  }

  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.flags = desc_.flags;
  info.imageType = desc_.type;
  info.format = desc_.format;
  info.extent = desc_.extent;
  info.mipLevels = desc_.mip_levels;
  info.arrayLayers = desc_.array_layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc_.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  check(vkCreateImage(context.device(), &info, nullptr, &image_),
        ("vkCreateImage for " + label).c_str());
  context.set_debug_name(VK_OBJECT_TYPE_IMAGE, reinterpret_cast<uint64_t>(image_), desc_.name);
}

VkMemoryRequirements Image::memory_requirements() const {
  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(context_->device(), image_, &requirements);
  return requirements;
}

void Image::bind_memory(const Allocation& memory) {
  check(vkBindImageMemory(context_->device(), image_, memory.memory, memory.offset),
        ("vkBindImageMemory for image \"" + desc_.name + "\"").c_str());
  allocation_ = memory;
  owns_memory_ = false;
}

Image::~Image() {
  destroy();
}

Image::Image(Image&& other) noexcept
    : context_(other.context_),
      desc_(std::move(other.desc_)),
      image_(std::exchange(other.image_, VK_NULL_HANDLE)),
      allocation_(std::exchange(other.allocation_, Allocation{})),
      owns_memory_(other.owns_memory_),
      aspect_(other.aspect_),
      whole_view_(std::exchange(other.whole_view_, VK_NULL_HANDLE)),
      mip_views_(std::move(other.mip_views_)),
      layer_views_(std::move(other.layer_views_)) {
  other.mip_views_.clear();
  other.layer_views_.clear();
}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    destroy();
    context_ = other.context_;
    desc_ = std::move(other.desc_);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    allocation_ = std::exchange(other.allocation_, Allocation{});
    owns_memory_ = other.owns_memory_;
    aspect_ = other.aspect_;
    whole_view_ = std::exchange(other.whole_view_, VK_NULL_HANDLE);
    mip_views_ = std::move(other.mip_views_);
    layer_views_ = std::move(other.layer_views_);
    other.mip_views_.clear();
    other.layer_views_.clear();
  }
  return *this;
}

void Image::destroy() {
  if (!context_) return;
  VkDevice device = context_->device();
  if (whole_view_) vkDestroyImageView(device, whole_view_, nullptr);
  for (auto& [mip, view] : mip_views_) vkDestroyImageView(device, view, nullptr);
  for (auto& [key, view] : layer_views_) vkDestroyImageView(device, view, nullptr);
  whole_view_ = VK_NULL_HANDLE;
  mip_views_.clear();
  layer_views_.clear();
  if (image_) vkDestroyImage(device, image_, nullptr);
  if (allocation_.memory && owns_memory_) context_->allocator().free(allocation_);
  image_ = VK_NULL_HANDLE;
  allocation_ = Allocation{};
}

VkImageSubresourceRange Image::range() const {
  return {aspect_, 0, desc_.mip_levels, 0, desc_.array_layers};
}

VkImageViewType Image::whole_view_type() const {
  if (desc_.type == VK_IMAGE_TYPE_3D) return VK_IMAGE_VIEW_TYPE_3D;
  if ((desc_.flags & VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT) && desc_.array_layers % 6 == 0) {
    return desc_.array_layers == 6 ? VK_IMAGE_VIEW_TYPE_CUBE : VK_IMAGE_VIEW_TYPE_CUBE_ARRAY;
  }
  return desc_.array_layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY : VK_IMAGE_VIEW_TYPE_2D;
}

VkImageView Image::create_view(VkImageViewType type, uint32_t base_mip, uint32_t mip_count,
                               uint32_t base_layer, uint32_t layer_count) {
  VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  info.image = image_;
  info.viewType = type;
  info.format = desc_.format;
  info.subresourceRange = {aspect_, base_mip, mip_count, base_layer, layer_count};
  VkImageView view = VK_NULL_HANDLE;
  check(vkCreateImageView(context_->device(), &info, nullptr, &view),
        ("vkCreateImageView for image \"" + desc_.name + "\"").c_str());
  context_->set_debug_name(VK_OBJECT_TYPE_IMAGE_VIEW, reinterpret_cast<uint64_t>(view),
                           desc_.name + ".view");
  return view;
}

VkImageView Image::view() {
  if (!whole_view_) {
    whole_view_ = create_view(whole_view_type(), 0, desc_.mip_levels, 0, desc_.array_layers);
  }
  return whole_view_;
}

VkImageView Image::view(uint32_t mip) {
  if (mip >= desc_.mip_levels) {
    throw Error("image \"" + desc_.name + "\": view of mip " + std::to_string(mip) +
                ", but it has " + std::to_string(desc_.mip_levels) + " mips");
  }
  auto found = mip_views_.find(mip);
  if (found != mip_views_.end()) return found->second;
  VkImageView created = create_view(whole_view_type(), mip, 1, 0, desc_.array_layers);
  mip_views_[mip] = created;
  return created;
}

VkImageView Image::layer_view(uint32_t layer, uint32_t mip) {
  if (desc_.type == VK_IMAGE_TYPE_3D) {
    throw Error("image \"" + desc_.name + "\": layer_view() is for 2D images, it is 3D");
  }
  if (layer >= desc_.array_layers || mip >= desc_.mip_levels) {
    throw Error("image \"" + desc_.name + "\": layer_view(" + std::to_string(layer) + ", " +
                std::to_string(mip) + ") is outside its " + std::to_string(desc_.array_layers) +
                " layers and " + std::to_string(desc_.mip_levels) + " mips");
  }
  auto key = std::make_pair(layer, mip);
  auto found = layer_views_.find(key);
  if (found != layer_views_.end()) return found->second;
  VkImageView created = create_view(VK_IMAGE_VIEW_TYPE_2D, mip, 1, layer, 1);
  layer_views_[key] = created;
  return created;
}

void Image::transition(VkCommandBuffer cmd, VkImageLayout from, VkImageLayout to) {
  image_barrier(cmd, image_, range(), from, to, kAnything, kAnything);
}

bool Image::can_generate_mips() const {
  VkFormatProperties properties;
  vkGetPhysicalDeviceFormatProperties(context_->physical_device(), desc_.format, &properties);
  VkFormatFeatureFlags need = VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                              VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  return (properties.optimalTilingFeatures & need) == need;
}

void Image::record_generate_mips(VkCommandBuffer cmd, VkImageLayout current_layout,
                                 VkImageLayout final_layout) {
  const uint32_t layers = desc_.array_layers;
  if (desc_.mip_levels == 1) {
    image_barrier(cmd, image_, range(), current_layout, final_layout, kAnything, kAnything);
    return;
  }
  if (!can_generate_mips()) {
    throw Error("image \"" + desc_.name + "\": cannot generate mips, " + context_->device_name() +
                " cannot linearly blit " + format_name(desc_.format));
  }
  image_barrier(cmd, image_, {aspect_, 0, 1, 0, layers}, current_layout,
                VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kAnything, kTransferRead);
  image_barrier(cmd, image_, {aspect_, 1, desc_.mip_levels - 1, 0, layers},
                VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kAnything,
                kTransferWrite);
  for (uint32_t mip = 1; mip < desc_.mip_levels; ++mip) {
    VkExtent3D src = mip_extent(desc_.extent, mip - 1);
    VkExtent3D dst = mip_extent(desc_.extent, mip);
    VkImageBlit2 blit{VK_STRUCTURE_TYPE_IMAGE_BLIT_2};
    blit.srcSubresource = {aspect_, mip - 1, 0, layers};
    blit.srcOffsets[1] = {static_cast<int32_t>(src.width), static_cast<int32_t>(src.height),
                          static_cast<int32_t>(src.depth)};
    blit.dstSubresource = {aspect_, mip, 0, layers};
    blit.dstOffsets[1] = {static_cast<int32_t>(dst.width), static_cast<int32_t>(dst.height),
                          static_cast<int32_t>(dst.depth)};
    VkBlitImageInfo2 info{VK_STRUCTURE_TYPE_BLIT_IMAGE_INFO_2};
    info.srcImage = image_;
    info.srcImageLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    info.dstImage = image_;
    info.dstImageLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    info.regionCount = 1;
    info.pRegions = &blit;
    info.filter = VK_FILTER_LINEAR;
    vkCmdBlitImage2(cmd, &info);
    image_barrier(cmd, image_, {aspect_, mip, 1, 0, layers}, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kTransferWrite, kTransferRead);
  }
  image_barrier(cmd, image_, range(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, final_layout,
                kTransferWrite, kAnything);
}

void Image::upload(const void* pixels, VkDeviceSize size, VkImageLayout final_layout,
                   bool generate_mips) {
  const VkExtent3D e = desc_.extent;
  const VkDeviceSize expected = VkDeviceSize(e.width) * e.height * e.depth *
                                bytes_per_texel(desc_.format) * desc_.array_layers;
  if (size != expected) {
    throw Error("upload to image \"" + desc_.name + "\": got " + std::to_string(size) +
                " bytes, expected " + std::to_string(expected) + " (" + extent_text(e) + " x " +
                std::to_string(desc_.array_layers) + " layers of " + format_name(desc_.format) +
                ")");
  }
  if (generate_mips && desc_.mip_levels > 1 && !can_generate_mips()) {
    throw Error("image \"" + desc_.name + "\": cannot generate mips, " + context_->device_name() +
                " cannot linearly blit " + format_name(desc_.format));
  }
  Buffer staging(*context_, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::CpuToGpu,
                 desc_.name + ".staging");
  staging.upload(pixels, size);
  context_->immediate_submit([&](VkCommandBuffer cmd) {
    image_barrier(cmd, image_, range(), VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kAnything, kTransferWrite);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {aspect_, 0, 0, desc_.array_layers};
    copy.imageExtent = e;
    vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &copy);
    if (generate_mips && desc_.mip_levels > 1) {
      image_barrier(cmd, image_, {aspect_, 0, 1, 0, desc_.array_layers},
                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                    kTransferWrite, kTransferRead);
      record_generate_mips(cmd, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, final_layout);
    } else {
      image_barrier(cmd, image_, range(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout,
                    kTransferWrite, kAnything);
    }
  });
}

void Image::upload_mip(const void* pixels, VkDeviceSize size, uint32_t mip, uint32_t layer,
                       VkImageLayout current_layout, VkImageLayout final_layout) {
  if (mip >= desc_.mip_levels || layer >= desc_.array_layers) {
    throw Error("upload to image \"" + desc_.name + "\": mip " + std::to_string(mip) + " layer " +
                std::to_string(layer) + " is outside its " + std::to_string(desc_.mip_levels) +
                " mips and " + std::to_string(desc_.array_layers) + " layers");
  }
  const VkExtent3D e = mip_extent(desc_.extent, mip);
  const VkDeviceSize expected =
      VkDeviceSize(e.width) * e.height * e.depth * bytes_per_texel(desc_.format);
  if (size != expected) {
    throw Error("upload to image \"" + desc_.name + "\" mip " + std::to_string(mip) + ": got " +
                std::to_string(size) + " bytes, expected " + std::to_string(expected) + " (" +
                extent_text(e) + " of " + format_name(desc_.format) + ")");
  }
  Buffer staging(*context_, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUsage::CpuToGpu,
                 desc_.name + ".staging");
  staging.upload(pixels, size);
  context_->immediate_submit([&](VkCommandBuffer cmd) {
    image_barrier(cmd, image_, range(), current_layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  kAnything, kTransferWrite);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {aspect_, mip, layer, 1};
    copy.imageExtent = e;
    vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &copy);
    image_barrier(cmd, image_, range(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout,
                  kTransferWrite, kAnything);
  });
}

std::vector<uint8_t> Image::download(VkImageLayout current_layout, uint32_t mip, uint32_t layer) {
  if (mip >= desc_.mip_levels || layer >= desc_.array_layers) {
    throw Error("download of image \"" + desc_.name + "\": mip " + std::to_string(mip) + " layer " +
                std::to_string(layer) + " is outside its " + std::to_string(desc_.mip_levels) +
                " mips and " + std::to_string(desc_.array_layers) + " layers");
  }
  if (current_layout == VK_IMAGE_LAYOUT_UNDEFINED) {
    throw Error("download of image \"" + desc_.name +
                "\": its layout is VK_IMAGE_LAYOUT_UNDEFINED, so it has no contents to read");
  }
  const VkExtent3D e = mip_extent(desc_.extent, mip);
  const VkDeviceSize size =
      VkDeviceSize(e.width) * e.height * e.depth * bytes_per_texel(desc_.format);
  Buffer staging(*context_, size, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUsage::GpuToCpu,
                 desc_.name + ".readback");
  context_->immediate_submit([&](VkCommandBuffer cmd) {
    image_barrier(cmd, image_, range(), current_layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                  kAnything, kTransferRead);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {aspect_, mip, layer, 1};
    copy.imageExtent = e;
    vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1,
                           &copy);
    image_barrier(cmd, image_, range(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, current_layout,
                  kTransferRead, kAnything);
    VkBufferMemoryBarrier2 to_host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    to_host.srcStageMask = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
    to_host.srcAccessMask = VK_ACCESS_2_TRANSFER_WRITE_BIT;
    to_host.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
    to_host.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
    to_host.srcQueueFamilyIndex = to_host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_host.buffer = staging.handle();
    to_host.size = VK_WHOLE_SIZE;
    VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    dependency.bufferMemoryBarrierCount = 1;
    dependency.pBufferMemoryBarriers = &to_host;
    vkCmdPipelineBarrier2(cmd, &dependency);
  });
  std::vector<uint8_t> texels(size);
  staging.download(texels.data(), size);
  return texels;
}

}  // namespace voxgi::gpu
