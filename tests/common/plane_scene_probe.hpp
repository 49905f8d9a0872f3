#pragma once
// Geometry queries on the built-in "plane-*" scenes (a floor quad at y = 0 and box
// occluders), so that tests can tell, per pixel, which surface it sees and whether the
// light reaches it, independently of the renderer.

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

#include "engine/scene/scene.hpp"

namespace voxgi::test {

struct Box {
  glm::vec3 min;
  glm::vec3 max;
  Box grown(float margin) const { return {min - glm::vec3(margin), max + glm::vec3(margin)}; }
  // Smallest t in [t0, t1] where the ray enters the box, if it does.
  std::optional<float> hit(const glm::vec3& origin, const glm::vec3& dir, float t0, float t1) const;
};

// The built-in plane scenes, one per punctual light type, and a test-name-safe form of them.
inline const char* const kPlaneScenes[] = {"plane-point", "plane-spot", "plane-directional"};
inline std::string plane_scene_test_name(const char* scene) {
  std::string name = scene;
  for (char& c : name) c = c == '-' ? '_' : c;
  return name;
}

class PlaneSceneProbe {
 public:
  // Finds the flat instance at y = 0 (the floor) and treats every other instance as a box.
  explicit PlaneSceneProbe(const scene::Scene& scene);

  // World point of the floor seen through pixel (x, y), or nothing when the pixel sees an
  // occluder, the sky, or the floor closer than `edge_margin` to its border.
  std::optional<glm::vec3> floor_point(const glm::mat4& view_proj, uint32_t x, uint32_t y,
                                       uint32_t width, uint32_t height,
                                       float edge_margin = 0.05f) const;

  // Whether the segment from `p` to the light crosses an occluder grown by `margin`
  // (a negative margin shrinks it).
  bool occluded(const scene::Light& light, const glm::vec3& p, float margin) const;

  const scene::Material& floor_material() const { return floor_material_; }

 private:
  Box floor_{};
  scene::Material floor_material_;
  std::vector<Box> occluders_;
};

}  // namespace voxgi::test
