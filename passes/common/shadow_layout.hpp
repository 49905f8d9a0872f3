#pragma once
// The per-light shadow data written by common.shadow_maps and read by lighting passes.
// Mirrors shaders/lib/shadow_data.glsl. Light i owns array layers 6*i .. 6*i+5 of the
// shadow map image (a point light uses all six cube faces, other lights the first one).

#include <glm/glm.hpp>

#include "engine/graph/pass_helpers.hpp"

namespace voxgi::passes::common {

using graph::kShadowFacesPerLight;

// Matrices are relative to `origin` (clip = view_proj * (p - origin)): a view matrix that
// carries a large translation loses float precision for scenes far from the world origin.
struct ShadowLight {
  glm::mat4 view_proj[kShadowFacesPerLight];
  glm::vec4 origin;  // xyz: the projection centre in world space
  // x: faces rendered (0 = no shadow, 1, or 6 for a point light)
  // y: world size of one texel (orthographic) or per unit distance (perspective)
  // z: 1 for perspective projections, 0 for orthographic
  // w: unused
  glm::vec4 info;
};
static_assert(sizeof(ShadowLight) == graph::kShadowLightBytes);

}  // namespace voxgi::passes::common
