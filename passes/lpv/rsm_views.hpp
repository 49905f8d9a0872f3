#pragma once
// The cameras of the reflective shadow maps: one fitted orthographic view per directional
// light, one perspective view over a spot light's cone, six exact 90-degree cube faces per
// point light. Unlike the shadow maps' faces (92 degrees, so filtering stays inside a face),
// these partition the directions around the light: every direction belongs to one texel of
// one face, so no flux is injected twice.

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "engine/scene/scene.hpp"

namespace voxgi::passes::lpv {

inline constexpr uint32_t kRsmFacesPerLight = 6;

struct RsmView {
  glm::mat4 view_proj;  // relative to the light's origin: clip = view_proj * (p - origin)
  glm::vec3 origin;     // the light's position (the scene sphere's far side for directional)
  bool perspective = true;
  // Perspective: tan of half the field of view (the image plane at distance 1 spans
  // [-extent, extent]). Orthographic: half the side of the view in metres.
  float extent = 1.0f;
};

// The views of one light (1 or 6).
std::vector<RsmView> rsm_views(const scene::Light& light, const scene::BoundingSphere& sphere);

// Solid angle of the texel (x, y) of an n x n perspective face whose image plane at distance 1
// spans [-extent, extent]^2: exact (the rectangle's solid angle, not cos^3 x area), so the
// texels of six 90-degree faces sum to 4 pi.
double rsm_texel_solid_angle(uint32_t x, uint32_t y, uint32_t n, double extent);

}  // namespace voxgi::passes::lpv
