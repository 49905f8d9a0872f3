#pragma once
// Contract: the shadow-map data common.shadow_maps writes and lighting passes of any family
// read. GLSL twin: shaders/contracts/shadow_data.glsl. Light i owns array layers 6*i .. 6*i+5
// of the shadow map image (a point light uses all six cube faces, other lights the first one)
// and record i of the shadow matrices buffer.

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

#include "engine/gpu/pipeline.hpp"
#include "engine/graph/pass.hpp"

namespace voxgi::contracts {

inline constexpr uint32_t kShadowFacesPerLight = 6;
inline constexpr VkFormat kShadowMapFormat = VK_FORMAT_D32_SFLOAT;

// std430 record of one light. Matrices are relative to `origin` (clip = view_proj * (p -
// origin)): a view matrix that carries a large translation loses float precision for scenes
// far from the world origin.
struct ShadowLight {
  glm::mat4 view_proj[kShadowFacesPerLight];
  glm::vec4 origin;  // xyz: the projection centre in world space
  // x: faces rendered (0 = no shadow, 1, or 6 for a point light)
  // y: world size of one texel (orthographic) or per unit distance (perspective)
  // z: 1 for perspective projections, 0 for orthographic
  // w: unused
  glm::vec4 info;
};
inline constexpr VkDeviceSize kShadowLightBytes = sizeof(ShadowLight);
static_assert(kShadowLightBytes == 6 * 64 + 32);
static_assert(offsetof(ShadowLight, origin) == 6 * 64);
static_assert(offsetof(ShadowLight, info) == 6 * 64 + 16);

// A reader's optional slots "shadow_maps" (the depth array, sampled) and "shadow_matrices" (the
// ShadowLight records, a storage buffer), in compute.
graph::SlotSpec shadow_maps_input(std::string doc);
graph::SlotSpec shadow_matrices_input(std::string doc);

// Writes the bound slots "shadow_maps" (with the shadow-compare sampler) at `maps_binding` and
// "shadow_matrices" at `lights_binding`; returns how many lights' shadows both hold.
uint32_t write_shadow_inputs(const graph::PassContext& ctx, gpu::DescriptorWriter& writer,
                             uint32_t maps_binding, uint32_t lights_binding);

}  // namespace voxgi::contracts
