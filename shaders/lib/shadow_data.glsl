#ifndef VOXGI_SHADOW_DATA_GLSL
#define VOXGI_SHADOW_DATA_GLSL
// The shadow-map data the common.shadow_maps pass writes; mirrors passes/common/shadow_layout.hpp.
struct ShadowLight {
  mat4 view_proj[6];  // relative to origin: clip = view_proj * (p - origin)
  vec4 origin;
  vec4 info;  // faces, texel size, perspective, unused
};

// Cube face of a point light for a direction from the light: +X, -X, +Y, -Y, +Z, -Z.
uint shadow_cube_face(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y >= 0.0 ? 2u : 3u;
  return d.z >= 0.0 ? 4u : 5u;
}
#endif
