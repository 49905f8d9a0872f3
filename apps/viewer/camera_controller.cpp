#include "apps/viewer/camera_controller.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace voxgi::viewer {

namespace {
constexpr float kMaxPitch = 1.55f;  // just short of straight up, where yaw is undefined
}

void CameraController::reset(const scene::Camera& camera, float scene_extent) {
  base_ = camera;
  extent_ = scene_extent > 0.0f && std::isfinite(scene_extent) ? scene_extent : 1.0f;
  position_ = glm::vec3(camera.world[3]);
  const glm::vec3 forward = -glm::normalize(glm::vec3(camera.world[2]));
  yaw_ = std::atan2(forward.x, -forward.z);
  pitch_ = std::asin(std::clamp(forward.y, -1.0f, 1.0f));
  distance_ = std::max(0.5f * extent_, 1e-3f);
  moved_ = false;
  changed_ = true;
}

glm::vec3 CameraController::forward() const {
  return {std::sin(yaw_) * std::cos(pitch_), std::sin(pitch_), -std::cos(yaw_) * std::cos(pitch_)};
}

void CameraController::place(const glm::vec3& position, float yaw, float pitch) {
  position_ = position;
  yaw_ = yaw;
  pitch_ = std::clamp(pitch, -kMaxPitch, kMaxPitch);
  moved_ = true;
  changed_ = true;
}

void CameraController::move(const glm::vec3& local_direction, float amount) {
  const glm::vec3 f = forward();
  const glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
  const glm::vec3 up(0, 1, 0);
  const glm::vec3 delta =
      right * local_direction.x + up * local_direction.y + f * local_direction.z;
  place(position_ + delta * amount, yaw_, pitch_);
}

void CameraController::rotate(float yaw_delta, float pitch_delta) {
  if (mode_ == CameraMode::Fly) {
    place(position_, yaw_ + yaw_delta, pitch_ + pitch_delta);
    return;
  }
  const glm::vec3 target = position_ + forward() * distance_;
  yaw_ += yaw_delta;
  pitch_ = std::clamp(pitch_ + pitch_delta, -kMaxPitch, kMaxPitch);
  place(target - forward() * distance_, yaw_, pitch_);
}

void CameraController::zoom(float factor) {
  const glm::vec3 target = position_ + forward() * distance_;
  distance_ = std::clamp(distance_ * factor, 1e-3f * extent_, 100.0f * extent_);
  place(target - forward() * distance_, yaw_, pitch_);
}

void CameraController::set_position(const glm::vec3& position) {
  place(position, yaw_, pitch_);
}

scene::Camera CameraController::camera() const {
  if (!moved_) return base_;
  scene::Camera camera = base_;
  camera.world = glm::inverse(glm::lookAt(position_, position_ + forward(), glm::vec3(0, 1, 0)));
  return camera;
}

bool CameraController::take_changed() {
  const bool changed = changed_;
  changed_ = false;
  return changed;
}

}  // namespace voxgi::viewer
