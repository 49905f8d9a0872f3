#pragma once
// Contract: the filtered radiance volumes vct.filter writes and cone tracers of any family read
// (vct.cone_trace, dvs.voxel_bounce). GLSL twins: shaders/contracts/vct_volume_encoding.glsl
// (what a texel holds) and shaders/contracts/cone_trace.glsl (mip layout, bindings, sampling).
// Here: the slot names a reader binds them to and the sampler cone_trace.glsl expects.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

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

// The two facing volumes of the front-light mode (vct.filter writes them when they are bound,
// every cone tracer reads them when they are bound): per direction of travel the share of the
// voxels' opacity that lies across it, premultiplied and composited like the light, channel k
// for axis k; "facing_pos" for +X, +Y, +Z, "facing_neg" for -X, -Y, -Z. With them the six
// directional volumes hold only the light of the surfaces facing each direction, and a cone
// reads the light of its three axes over their facing shares (contracts/cone_trace.glsl,
// VCT_FRONT_LIGHT; docs/vct.md, "A surface lights only its front").
inline constexpr std::array<const char*, 2> kFacingSlots = {"facing_pos", "facing_neg"};

// True when a pass has both facing volumes bound (validate_front_light_slots makes sure it
// has both or neither).
bool front_light_bound(const graph::PassDeclaration& pass);
// For validate hooks: both facing slots or neither, and only beside the six directional ones.
void validate_front_light_slots(graph::PassCheck& check);
// The define cone_trace.glsl reads (VCT_FRONT_LIGHT): the volume array then holds eight
// samplers, the six directional volumes followed by facing_pos and facing_neg.
gpu::ShaderDefine front_light_define(bool front_light);
uint32_t volume_array_size(bool anisotropic, bool front_light);
// A reader's optional input slot for a filtered volume (rgba16f clipmap, sampled in compute),
// and for facing volume `slot`.
graph::SlotSpec filtered_volume_input(const char* name, std::string doc);
graph::SlotSpec facing_input(const char* slot);
// The volume array in cone_trace.glsl's order, each with `sampler`: the isotropic volume, or
// the six directional ones followed (front light) by the two facing volumes.
std::vector<VkDescriptorImageInfo> filtered_volume_images(graph::PassContext& ctx, bool anisotropic,
                                                          bool front_light, VkSampler sampler);

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
