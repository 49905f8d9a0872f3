#include "plane_scene_probe.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace voxgi::test {

std::optional<float> Box::hit(const glm::vec3& origin, const glm::vec3& dir, float t0,
                              float t1) const {
  for (int axis = 0; axis < 3; ++axis) {
    if (std::abs(dir[axis]) < 1e-12f) {
      if (origin[axis] < min[axis] || origin[axis] > max[axis]) return std::nullopt;
      continue;
    }
    float a = (min[axis] - origin[axis]) / dir[axis];
    float b = (max[axis] - origin[axis]) / dir[axis];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return std::nullopt;
  }
  return t0;
}

PlaneSceneProbe::PlaneSceneProbe(const scene::Scene& scene) {
  bool found_floor = false;
  for (const scene::Instance& instance : scene.instances()) {
    const scene::Primitive& primitive = scene.meshes[static_cast<size_t>(instance.mesh)]
                                            .primitives[static_cast<size_t>(instance.primitive)];
    Box box{glm::vec3(std::numeric_limits<float>::max()),
            glm::vec3(-std::numeric_limits<float>::max())};
    for (const scene::Vertex& v : primitive.vertices) {
      const glm::vec3 w = glm::vec3(instance.world * glm::vec4(v.position, 1.0f));
      box.min = glm::min(box.min, w);
      box.max = glm::max(box.max, w);
    }
    if (box.max.y - box.min.y < 1e-4f && std::abs(box.max.y) < 1e-4f) {
      floor_ = box;
      found_floor = true;
      floor_material_ = primitive.material >= 0
                            ? scene.materials[static_cast<size_t>(primitive.material)]
                            : scene::Material{};
    } else {
      occluders_.push_back(box);
    }
  }
  if (!found_floor) throw std::invalid_argument("plane scene probe: no floor at y = 0");
}

std::optional<glm::vec3> PlaneSceneProbe::floor_point(const glm::mat4& view_proj, uint32_t x,
                                                      uint32_t y, uint32_t width, uint32_t height,
                                                      float edge_margin) const {
  const glm::mat4 inverse = glm::inverse(view_proj);
  const float nx = (static_cast<float>(x) + 0.5f) / static_cast<float>(width) * 2.0f - 1.0f;
  const float ny = (static_cast<float>(y) + 0.5f) / static_cast<float>(height) * 2.0f - 1.0f;
  glm::vec4 near_point = inverse * glm::vec4(nx, ny, 0.0f, 1.0f);
  glm::vec4 far_point = inverse * glm::vec4(nx, ny, 1.0f, 1.0f);
  const glm::vec3 origin = glm::vec3(near_point) / near_point.w;
  const glm::vec3 dir = glm::vec3(far_point) / far_point.w - origin;
  if (std::abs(dir.y) < 1e-9f) return std::nullopt;
  const float t = -origin.y / dir.y;
  if (t <= 0.0f) return std::nullopt;
  const glm::vec3 p = origin + dir * t;
  if (p.x < floor_.min.x + edge_margin || p.x > floor_.max.x - edge_margin ||
      p.z < floor_.min.z + edge_margin || p.z > floor_.max.z - edge_margin) {
    return std::nullopt;
  }
  for (const Box& box : occluders_) {
    // Pixels near an occluder's silhouette are left out: their footprint straddles two surfaces.
    if (box.grown(0.02f).hit(origin, dir, 0.0f, t)) return std::nullopt;
  }
  return p;
}

bool PlaneSceneProbe::occluded(const scene::Light& light, const glm::vec3& p, float margin) const {
  glm::vec3 dir;
  float t1;
  if (light.type == scene::LightType::Directional) {
    dir = -glm::normalize(light.direction);
    t1 = 1e4f;
  } else {
    dir = light.position - p;
    t1 = 1.0f;
  }
  for (const Box& box : occluders_) {
    if (box.grown(margin).hit(p, dir, 1e-4f, t1)) return true;
  }
  return false;
}

}  // namespace voxgi::test
