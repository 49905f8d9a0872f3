#pragma once
// The one way frames are made from a camera: the CLI, the bench, the viewer, the samples and
// the test harnesses all turn their view into an executor frame here, so what "changed" means
// to the passes' skip decisions (and that an executor's first frame recomputes everything) is
// decided in one place.

#include <glm/glm.hpp>

#include <cstdint>

#include "engine/graph/executor.hpp"
#include "engine/scene/scene.hpp"

namespace voxgi::runtime {

// Where the frame is seen from.
struct FrameView {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};
  glm::vec3 position{0.0f};
  float znear = 0.1f;
  float zfar = 100.0f;
};
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

// Renders frames of one executor and counts them; the first frame after construction or
// restart() (a rebuilt graph) treats everything as changed, whatever the caller says.
class FrameDriver {
 public:
  explicit FrameDriver(graph::Executor& executor) : executor_(executor) {}

  void render(const FrameView& view, double time, const FrameChanges& changes);
  void restart() { frames_ = 0; }
  uint64_t frames() const { return frames_; }

 private:
  graph::Executor& executor_;
  uint64_t frames_ = 0;
};

}  // namespace voxgi::runtime
