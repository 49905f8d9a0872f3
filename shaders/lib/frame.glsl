#ifndef VOXGI_FRAME_GLSL
#define VOXGI_FRAME_GLSL
// Mirrors voxgi::graph::FrameUniforms (engine/graph/frame.hpp).
struct FrameUniforms {
  mat4 view;
  mat4 proj;
  mat4 view_proj;
  mat4 inv_view;
  mat4 inv_proj;
  mat4 inv_view_proj;
  vec4 camera_position;
  vec4 viewport;  // width, height, 1/width, 1/height
  vec4 clip;      // znear, zfar, time, frame index
  vec4 scene_min; // xyz bounds, w light count
  vec4 scene_max;
};
#endif
