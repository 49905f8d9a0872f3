#pragma once
// The one way frames are made from a camera: the CLI, the bench, the viewer, the samples and
// the test harnesses all turn their view into an executor frame here, so what "changed" means
// to the passes' skip decisions is decided in one place.

#include <glm/glm.hpp>

#include <cstdint>

#include "engine/graph/executor.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::runtime {

// Where the frame is seen from (the executor's type).
using FrameView = graph::CameraView;
// A scene camera (its own aspect ratio when it has one, else the viewport's).
FrameView frame_view(const scene::Camera& camera, float viewport_aspect);
// From `eye` towards `target` through the lens of `camera` (field of view, clip planes); the
// up vector is +y unless the view is nearly vertical, then +z.
FrameView look_at_view(glm::vec3 eye, glm::vec3 target, const scene::Camera& camera,
                       float viewport_aspect);

// What changed since the previous frame (drives the passes' skip decisions).
struct FrameChanges {
  bool camera = true;
  bool lights = true;
  bool geometry = true;
};

// Renders frames of one executor and counts them. (The executor itself treats the first
// frame after a build as a change of everything.)
class FrameDriver {
 public:
  explicit FrameDriver(graph::Executor& executor) : executor_(executor) {}

  void render(const FrameView& view, double time, const FrameChanges& changes);
  uint64_t frames() const { return frames_; }
  void restart() { frames_ = 0; }  // counting from a rebuild

 private:
  graph::Executor& executor_;
  uint64_t frames_ = 0;
};

}  // namespace voxgi::runtime
