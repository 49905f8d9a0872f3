#pragma once
// Per-frame data every pass sees: camera, viewport and what changed since the last frame.

#include <glm/glm.hpp>

#include <cstdint>

namespace voxgi::gpu {
class Buffer;
}

namespace voxgi::graph {

// Mirrors `FrameUniforms` in shaders/lib/frame.glsl (std140). Keep the two in step.
// Where a frame is seen from.
struct CameraView {
  glm::mat4 view{1.0f};
  glm::mat4 proj{1.0f};
  glm::vec3 position{0.0f};
  float znear = 0.1f;
  float zfar = 100.0f;
};

struct alignas(16) FrameUniforms {
  glm::mat4 view;
  glm::mat4 proj;
  glm::mat4 view_proj;
  glm::mat4 inv_view;
  glm::mat4 inv_proj;
  glm::mat4 inv_view_proj;
  glm::vec4 camera_position;  // xyz, w = 1
  glm::vec4 viewport;         // width, height, 1/width, 1/height
  glm::vec4 clip;             // znear, zfar, time (s), frame index
  glm::vec4 scene_min;        // xyz: scene bounds, w: light count
  glm::vec4 scene_max;        // xyz, w: unused
};
static_assert(sizeof(FrameUniforms) == 6 * 64 + 5 * 16);

struct FrameInfo {
  uint64_t index = 0;  // frames rendered since the graph was compiled
  double time = 0.0;   // scene time in seconds (animations)
  uint32_t width = 0;
  uint32_t height = 0;
  FrameUniforms uniforms{};
  gpu::Buffer* uniform_buffer = nullptr;  // holds `uniforms`, bind as a uniform buffer

  // What changed since the previous frame; all true on the first frame after a compile.
  bool first_frame = true;
  bool camera_changed = true;
  bool lights_changed = true;
  bool geometry_changed = true;  // a node moved, or the scene was replaced
};

}  // namespace voxgi::graph
