#include "engine/runtime/frame_driver.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace voxgi::runtime {

FrameView frame_view(const scene::Camera& camera, float viewport_aspect) {
  FrameView view;
  view.view = scene::view_matrix(camera);
  view.proj = scene::projection_matrix(camera, viewport_aspect);
  view.position = glm::vec3(camera.world[3]);
  view.znear = camera.znear;
  view.zfar = camera.zfar;
  return view;
}

FrameView look_at_view(glm::vec3 eye, glm::vec3 target, const scene::Camera& camera,
                       float viewport_aspect) {
  const bool vertical = std::abs(glm::normalize(target - eye).y) > 0.99f;
  FrameView view;
  view.view = glm::lookAt(eye, target, vertical ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0));
  view.proj = scene::projection_matrix(camera, viewport_aspect);
  view.position = eye;
  view.znear = camera.znear;
  view.zfar = camera.zfar;
  return view;
}

void FrameDriver::render(const FrameView& view, double time, const FrameChanges& changes) {
  graph::Executor::FrameInput input;
  input.camera = view;
  input.time = time;
  input.camera_changed = changes.camera;
  input.lights_changed = changes.lights;
  input.geometry_changed = changes.geometry;
  executor_.render(input);
  ++frames_;
}

}  // namespace voxgi::runtime
