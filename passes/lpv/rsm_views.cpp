#include "passes/lpv/rsm_views.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace voxgi::passes::lpv {
namespace {

glm::vec3 up_for(const glm::vec3& direction) {
  return std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
}

// Solid angle of the rectangle [0, x] x [0, y] on the plane at distance 1, seen from the
// origin (signed by the signs of x and y).
double corner_solid_angle(double x, double y) {
  return std::atan2(x * y, std::sqrt(1.0 + x * x + y * y));
}

}  // namespace

std::vector<RsmView> rsm_views(const scene::Light& light, const scene::BoundingSphere& sphere) {
  const glm::vec3 dir = glm::normalize(light.direction);
  if (light.type == scene::LightType::Directional) {
    const float r = sphere.radius;
    RsmView view;
    view.origin = sphere.center - dir * (2.0f * r);
    view.view_proj = glm::ortho(-r, r, -r, r, r * 0.5f, r * 3.5f) *
                     glm::lookAt(glm::vec3(0.0f), dir, up_for(dir));
    view.perspective = false;
    view.extent = r;
    return {view};
  }
  const float zfar =
      std::max(glm::length(sphere.center - light.position) + sphere.radius, 1e-3f) * 1.01f;
  const float znear = std::max(zfar * 1e-4f, 1e-5f);
  if (light.type == scene::LightType::Spot) {
    // The cone plus a margin of a degree; the spot falloff is zero beyond the outer angle.
    const float half = std::min(light.outer_cone + glm::radians(1.0f), glm::radians(85.0f));
    RsmView view;
    view.origin = light.position;
    view.view_proj = glm::perspective(2.0f * half, 1.0f, znear, zfar) *
                     glm::lookAt(glm::vec3(0.0f), dir, up_for(dir));
    view.extent = std::tan(half);
    return {view};
  }
  static const glm::vec3 kFaceDirs[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                         {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  static const glm::vec3 kFaceUps[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1},
                                        {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  const glm::mat4 proj = glm::perspective(glm::radians(90.0f), 1.0f, znear, zfar);
  std::vector<RsmView> views(6);
  for (int face = 0; face < 6; ++face) {
    views[face].origin = light.position;
    views[face].view_proj = proj * glm::lookAt(glm::vec3(0.0f), kFaceDirs[face], kFaceUps[face]);
    views[face].extent = 1.0f;
  }
  return views;
}

double rsm_texel_solid_angle(uint32_t x, uint32_t y, uint32_t n, double extent) {
  const double step = 2.0 * extent / n;
  const double x0 = -extent + step * x, x1 = x0 + step;
  const double y0 = -extent + step * y, y1 = y0 + step;
  return corner_solid_angle(x1, y1) - corner_solid_angle(x0, y1) - corner_solid_angle(x1, y0) +
         corner_solid_angle(x0, y0);
}

}  // namespace voxgi::passes::lpv
