#pragma once
// Helpers the dvs passes share: compute pipelines from shaders/dvs, slot declarations for
// voxel clipmaps, dispatch sizes over a volume, and input-version tracking for skipping.

#include <cstdint>
#include <string>
#include <vector>

#include "engine/gpu/pipeline.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::passes::dvs {

// A compute pipeline from shaders/dvs/<file>: set 0 holds `bindings` (push descriptors), set 1
// the scene's descriptor set when `with_scene_set` is true.
gpu::ComputePipeline make_dvs_compute(const graph::PassContext& ctx, const std::string& file,
                                      std::vector<gpu::Binding> bindings,
                                      uint32_t push_constant_size, bool with_scene_set,
                                      std::vector<gpu::ShaderDefine> defines = {});

// Binds the scene's descriptor set as set 1 of a compute pipeline.
void bind_scene_set(const graph::PassContext& ctx, const gpu::ComputePipeline& pipeline);

// A clipmap read with texelFetch or a sampler in compute.
graph::SlotSpec clipmap_input(const char* name, const char* doc, bool optional = false,
                              std::vector<VkFormat> formats = {});
// A buffer read as a storage buffer in compute (e.g. voxel.clipmap_info).
graph::SlotSpec buffer_input(const char* name, const char* doc, bool optional = false);
// An rgba16f clipmap written as a storage image in compute (its mip 0, or the bound mip).
graph::SlotSpec radiance_volume_output(const char* name, const char* doc, bool optional = false);

// The view a storage write of a volume slot goes to: the bound mip, or mip 0 when the slot is
// bound to the whole image (storage views hold one mip level).
VkImageView storage_view(const graph::BoundResource& resource);

// Workgroup edge of the family's 3D compute shaders (local size kVolumeTile^3).
inline constexpr uint32_t kVolumeTile = 4;
void dispatch_over_volume(VkCommandBuffer cmd, VkExtent3D extent);

// The voxel clipmap info buffer (shaders/lib/voxel_clipmap.glsl): 16 + 16 + 8 * 32 bytes.
inline constexpr VkDeviceSize kClipmapInfoSize = 288;

// Remembers the resource versions of a pass's inputs at its last execute(), so that
// skip_reason() can tell whether any of them has been written since.
class InputVersions {
 public:
  explicit InputVersions(std::vector<std::string> slots) : slots_(std::move(slots)) {}
  // True before the first store() and whenever a bound slot's version differs from the stored.
  bool changed(const graph::PassContext& ctx) const;
  void store(const graph::PassContext& ctx);
  void reset() { stored_.clear(); }

 private:
  std::vector<uint64_t> current(const graph::PassContext& ctx) const;
  std::vector<std::string> slots_;
  std::vector<uint64_t> stored_;
};

}  // namespace voxgi::passes::dvs
