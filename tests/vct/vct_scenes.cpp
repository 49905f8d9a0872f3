#include "tests/vct/vct_scenes.hpp"

#include "engine/scene/scene_builder.hpp"
#include "tests/common/hard_case_scenes.hpp"

namespace voxgi::test {

scene::Scene furnace_box(float le, bool metal_floor) {
  scene::SceneBuilder b("furnace");
  const int white = b.add_material(matte(glm::vec3(1.0f), glm::vec3(le)));
  add_closed_box(b, glm::vec3(-0.5f), glm::vec3(0.5f), 0.08f, white);
  if (metal_floor) {
    scene::Material metal = matte(glm::vec3(1.0f), glm::vec3(le));
    metal.metallic = 1.0f;
    metal.roughness = 0.2f;
    // A metal plate on the floor, thin enough to stay inside the floor's voxels.
    b.add_quad("metal", {-0.5f, 0.0005f - 0.5f, -0.5f}, {0, 0, 1}, {1, 0, 0},
               b.add_material(metal));
  }
  b.add_camera("inside", {0.0f, 0.05f, -0.3f}, {0.1f, 0.0f, 0.5f}, 1.2f);
  return b.finish();
}

scene::Scene two_rooms(int camera_room) {
  scene::SceneBuilder b("two_rooms");
  const int white = b.add_material(matte(glm::vec3(0.8f)));
  add_closed_box(b, glm::vec3(0.0f), glm::vec3(2.0f, 1.0f, 1.0f), 2.0f * kTwoRoomsVoxel, white);
  b.add_box("partition", {1.0f, 0.5f, 0.5f}, {kTwoRoomsVoxel, 1.0f, 1.0f}, white);
  scene::Light light;
  light.type = scene::LightType::Point;
  light.intensity = 2.0f;
  b.add_light(light, {0.5f, 0.6f, 0.5f});
  if (camera_room == 0) {
    b.add_camera("room0", {0.9f, 0.5f, 0.5f}, {0.0f, 0.5f, 0.5f}, 1.2f);
  } else {
    b.add_camera("room1", {1.1f, 0.5f, 0.5f}, {2.0f, 0.5f, 0.5f}, 1.2f);
  }
  return b.finish();
}

}  // namespace voxgi::test
