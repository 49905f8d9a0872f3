#pragma once
// Contract: the filtered radiance volumes vct.filter writes and cone tracers of any family read
// (vct.cone_trace, dvs.voxel_bounce). GLSL twins: shaders/contracts/vct_volume_encoding.glsl
// (what a texel holds) and shaders/contracts/cone_trace.glsl (mip layout, bindings, sampling).
// Here: the slot names a reader binds them to and the sampler cone_trace.glsl expects.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>

#include "engine/gpu/shader_compiler.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::gpu {
class Context;
}

namespace voxgi::contracts {

// The define cone_trace.glsl needs for volumes of `clipmap_levels` levels: with one level the
// window may be stored without the wrap (it stays put unless it follows the camera), and the
// tracer then reads beyond it as empty; clipmaps of several levels keep the wrapped path.
gpu::ShaderDefine unwrapped_windows_define(uint32_t clipmap_levels);

// cone_trace.glsl's refinement where a cone meets a surface (vct_sample_step): the define for
// `levels` levels of detail finer (0: off), and the pass parameter "refine" that sets it, the
// same for every pass that traces cones but for its default: the gathers refine two levels, the
// voxel bounces of dvs one (docs/error-budget.md, twenty-seventh round).
gpu::ShaderDefine refine_levels_define(int levels);
graph::ParamSpec refine_levels_param(int default_levels);

// The longest cone, the pass parameter "max_distance" of every pass that traces cones, in the
// scene's units: 0 (the default) is no limit, cones end where they are opaque or leave the
// clipmap. (A default of 100 "metres" cut every cone of a scene modelled in centimetres at
// 1 m: the conference room's one-bounce light was 94% dark.) cone_max_distance turns its value
// into the length the shaders compare with.
graph::ParamSpec cone_max_distance_param();
float cone_max_distance(double value);

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
