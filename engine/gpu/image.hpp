#pragma once
// 2D, 2D-array and 3D images with their memory and cached views, plus upload, download,
// mip generation and layout transitions for tools and tests.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "engine/gpu/memory.hpp"

namespace voxgi::gpu {

class Context;

struct ImageDesc {
  VkImageType type = VK_IMAGE_TYPE_2D;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent3D extent{1, 1, 1};
  uint32_t mip_levels = 1;  // 0 is treated as full_mip_count(extent)
  uint32_t array_layers = 1;
  VkImageUsageFlags usage = 0;
  std::string name;
  VkImageCreateFlags flags = 0;  // e.g. CUBE_COMPATIBLE
};

// floor(log2(max dimension)) + 1.
uint32_t full_mip_count(VkExtent3D extent);
// DEPTH for depth formats, COLOR otherwise.
VkImageAspectFlags aspect_of(VkFormat format);
bool is_depth_format(VkFormat format);
// Size of one texel; throws Error for formats the project does not use.
uint32_t bytes_per_texel(VkFormat format);
// "VK_FORMAT_R8G8B8A8_UNORM" for the formats above, else "VkFormat(other)".
const char* format_name(VkFormat format);
// The extent of mip level `mip` (each dimension halved, at least 1).
VkExtent3D mip_extent(VkExtent3D extent, uint32_t mip);

class Image {
 public:
  // Throws Error for a zero extent, an unsupported format/usage combination (naming the
  // format, usage and image name) or out-of-memory. TRANSFER_SRC and TRANSFER_DST are
  // always added to usage so upload(), download() and mip generation work.
  Image(Context& context, const ImageDesc& desc);
  // The same without memory: bind_memory() binds memory the caller owns (SharedMemory).
  Image(Context& context, const ImageDesc& desc, BindLater);
  ~Image();
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;

  VkImage handle() const { return image_; }
  const ImageDesc& desc() const { return desc_; }
  VkImageAspectFlags aspect() const { return aspect_; }
  VkFormat format() const { return desc_.format; }
  VkExtent3D extent() const { return desc_.extent; }

  // All mips and layers: VIEW_TYPE_2D for one layer, 2D_ARRAY for several, 3D for 3D,
  // CUBE / CUBE_ARRAY for cube-compatible images with a multiple of 6 layers.
  VkImageView view();
  // One mip, all layers (same view type as view()); cached.
  VkImageView view(uint32_t mip);
  // One layer and mip as a 2D view (a render target); cached. Not for 3D images.
  VkImageView layer_view(uint32_t layer, uint32_t mip = 0);

  VkImageSubresourceRange range() const;
  VkDeviceSize memory_size() const { return allocation_.size; }
  VkMemoryRequirements memory_requirements() const;
  // Once, for an image made with BindLater; the memory stays the caller's.
  void bind_memory(const Allocation& memory);

  // Replaces mip 0 of every layer (contents before are discarded, so the image may be in
  // any layout) with `pixels`: layers one after the other, each tightly packed (for a 3D
  // image: the whole volume). size must equal that byte count. With generate_mips the
  // other mips are filled with linear blits (throws Error if the format cannot be
  // linearly blitted on this device). Ends with every mip and layer in final_layout.
  // Waits for the queue.
  void upload(const void* pixels, VkDeviceSize size, VkImageLayout final_layout,
              bool generate_mips = false);
  // Replaces one mip of one layer (or the whole volume of one mip for 3D), tightly packed.
  // current_layout is the layout every subresource is in now; the image ends in
  // final_layout. Waits for the queue.
  void upload_mip(const void* pixels, VkDeviceSize size, uint32_t mip, uint32_t layer,
                  VkImageLayout current_layout, VkImageLayout final_layout);
  // Tightly packed texels of one mip of one layer (3D: all slices of that mip). The image
  // must be in current_layout (all subresources) and is left in it. Waits for the queue.
  std::vector<uint8_t> download(VkImageLayout current_layout, uint32_t mip = 0, uint32_t layer = 0);

  // Full-range layout transition (synchronization2, all-commands scope) for tools and
  // tests; graph passes never need it.
  void transition(VkCommandBuffer cmd, VkImageLayout from, VkImageLayout to);
  // Records blits from mip 0 down to the last mip, all layers. Mip 0 must be in
  // current_layout, the other mips' contents are discarded; ends in final_layout.
  void record_generate_mips(VkCommandBuffer cmd, VkImageLayout current_layout,
                            VkImageLayout final_layout);
  // Whether this device can linearly blit (and so generate mips of) the format.
  bool can_generate_mips() const;

 private:
  VkImageView create_view(VkImageViewType type, uint32_t base_mip, uint32_t mip_count,
                          uint32_t base_layer, uint32_t layer_count);
  VkImageViewType whole_view_type() const;
  void destroy();

  Context* context_ = nullptr;
  ImageDesc desc_;
  VkImage image_ = VK_NULL_HANDLE;
  Allocation allocation_{};
  bool owns_memory_ = true;
  VkImageAspectFlags aspect_ = VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageView whole_view_ = VK_NULL_HANDLE;
  std::map<uint32_t, VkImageView> mip_views_;
  std::map<std::pair<uint32_t, uint32_t>, VkImageView> layer_views_;
};

}  // namespace voxgi::gpu
