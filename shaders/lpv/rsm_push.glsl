#ifndef VOXGI_LPV_RSM_PUSH_GLSL
#define VOXGI_LPV_RSM_PUSH_GLSL
// Push constants of lpv.rsm (RsmPush in passes/lpv/rsm_pass.cpp).
layout(push_constant) uniform RsmPush {
  mat4 view_proj;  // relative to origin
  vec4 origin;     // xyz: projection centre; w: the light's index
  // x: 1 perspective, 0 orthographic; y: tan(half fov) or half the orthographic side (m);
  // z: the map's edge in texels
  vec4 info;
} pc;
#endif
