#ifndef VOXGI_SHADOW_DATA_GLSL
#define VOXGI_SHADOW_DATA_GLSL
// The shadow-map data the common.shadow_maps pass writes; mirrors passes/common/shadow_layout.hpp.
struct ShadowLight {
  mat4 view_proj[6];  // relative to origin: clip = view_proj * (p - origin)
  vec4 origin;
  vec4 info;  // faces, texel size, perspective, unused
};

// World-space edge of one shadow-map texel at `distance_to_light` (perspective maps widen
// with distance).
float shadow_texel_world(ShadowLight s, float distance_to_light) {
  return s.info.z > 0.5 ? s.info.y * distance_to_light : s.info.y;
}

// The smallest offset off a surface that keeps a lookup out of its own float32 rounding: far
// from the origin the spacing of positions (|p| * 2^-23) exceeds a texel and would make every
// surface shadow itself.
float shadow_min_offset(vec3 p) {
  vec3 a = abs(p);
  return 8.0 * max(a.x, max(a.y, a.z)) * 1.2e-7;
}

// Cube face of a point light for a direction from the light: +X, -X, +Y, -Y, +Z, -Z.
uint shadow_cube_face(vec3 d) {
  vec3 a = abs(d);
  if (a.x >= a.y && a.x >= a.z) return d.x >= 0.0 ? 0u : 1u;
  if (a.y >= a.z) return d.y >= 0.0 ? 2u : 3u;
  return d.z >= 0.0 ? 4u : 5u;
}
#endif
