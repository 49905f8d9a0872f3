#pragma once
// The per-light shadow data written by common.shadow_maps and read by lighting passes.
// Mirrors shaders/common/shadow_data.glsl. Light i owns array layers 6*i .. 6*i+5 of the
// shadow map image (a point light uses all six cube faces, other lights the first one).

#include <glm/glm.hpp>

namespace voxgi::passes::common {

inline constexpr uint32_t kShadowFacesPerLight = 6;

struct ShadowLight {
  glm::mat4 view_proj[kShadowFacesPerLight];
  // x: faces rendered (0 = no shadow, 1, or 6 for a point light)
  // y: world size of one texel (orthographic) or per unit distance (perspective)
  // z: 1 for perspective projections, 0 for orthographic
  // w: unused
  glm::vec4 info;
};
static_assert(sizeof(ShadowLight) == 6 * 64 + 16);

}  // namespace voxgi::passes::common
