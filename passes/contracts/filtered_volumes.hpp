#pragma once
// Contract: the filtered radiance volumes vct.filter writes and cone tracers of any family read
// (vct.cone_trace, dvs.voxel_bounce). GLSL twins: shaders/contracts/vct_volume_encoding.glsl
// (what a texel holds) and shaders/contracts/cone_trace.glsl (mip layout, bindings, sampling).
// Here: the slot names a reader binds them to and the sampler cone_trace.glsl expects.

#include <vulkan/vulkan.h>

#include <array>

namespace voxgi::gpu {
class Context;
}

namespace voxgi::contracts {

// "filtered" (isotropic) or the six directional volumes, in the order +X, -X, +Y, -Y, +Z, -Z.
inline constexpr const char* kFilteredSlot = "filtered";
inline constexpr std::array<const char*, 6> kDirectionalSlots = {"pos_x", "neg_x", "pos_y",
                                                                 "neg_y", "pos_z", "neg_z"};

// The sampler cone_trace.glsl needs for the filtered volumes: linear, whole mips, REPEAT, no
// anisotropic filtering. Owned by the pass that creates it.
class VolumeSampler {
 public:
  explicit VolumeSampler(gpu::Context& context);
  ~VolumeSampler();
  VolumeSampler(const VolumeSampler&) = delete;
  VolumeSampler& operator=(const VolumeSampler&) = delete;
  VkSampler handle() const { return sampler_; }

 private:
  gpu::Context& context_;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

}  // namespace voxgi::contracts
