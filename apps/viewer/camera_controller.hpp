#pragma once
// The viewer's camera: fly (move along the view, look with the mouse) or orbit (turn around a
// target, zoom towards it). Until the user moves it, it returns the scene camera it started
// from unchanged, so an untouched viewer frame matches `voxgi render` exactly.

#include <glm/glm.hpp>

#include "engine/scene/scene.hpp"

namespace voxgi::viewer {

enum class CameraMode { Fly, Orbit };

class CameraController {
 public:
  // `scene_extent`: the largest side of the scene bounds; movement speeds scale with it.
  void reset(const scene::Camera& camera, float scene_extent);

  void set_mode(CameraMode mode) { mode_ = mode; }
  CameraMode mode() const { return mode_; }

  // Fly: moves by `amount` (meters) along right (x), up (y) and forward (z).
  void move(const glm::vec3& local_direction, float amount);
  // Fly: turns the view; orbit: turns around the target. Radians.
  void rotate(float yaw_delta, float pitch_delta);
  // Orbit: multiplies the distance to the target (< 1 zooms in).
  void zoom(float factor);
  void set_position(const glm::vec3& position);

  scene::Camera camera() const;
  glm::vec3 position() const { return position_; }
  glm::vec3 forward() const;
  float extent() const { return extent_; }
  bool moved() const { return moved_; }
  // True once after any change; the frame's camera_changed flag.
  bool take_changed();

 private:
  void place(const glm::vec3& position, float yaw, float pitch);

  scene::Camera base_;
  CameraMode mode_ = CameraMode::Fly;
  glm::vec3 position_{0.0f};
  float yaw_ = 0.0f;       // around +Y; 0 looks along -Z
  float pitch_ = 0.0f;     // up is positive
  float distance_ = 1.0f;  // orbit: from the position to the target along the view
  float extent_ = 1.0f;
  bool moved_ = false;
  bool changed_ = true;
};

}  // namespace voxgi::viewer
