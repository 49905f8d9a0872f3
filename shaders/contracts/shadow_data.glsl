#ifndef VOXGI_SHADOW_DATA_GLSL
#define VOXGI_SHADOW_DATA_GLSL
// Contract: the shadow-map data common.shadow_maps writes and lighting passes of any family
// read. C++ twin: passes/contracts/shadow_data.hpp (std430, 416 bytes per light). No bindings.
#include "lib/sampling.glsl"
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

// 1 where the shadow map of light `s` (layers layer_base + face of `maps`) sees the surface
// point p (world space), by one hardware 2x2 PCF compare lookup. The lookup moves off the
// surface along `facing` by `offset` metres, or by two shadow-map texels or the float32 guard
// where those are larger. p must lie on the surface (a voxel's average surface plane, not its
// centre): then a small offset suffices, and a larger one would look past occluders close in
// front of the surface (a lamp's shade just under a ceiling) and let light through them.
float shadow_surface_visibility(sampler2DArrayShadow maps, ShadowLight s, float layer_base,
                                vec3 p, vec3 facing, float offset, float distance_to_light) {
  uint faces = uint(s.info.x + 0.5);
  if (faces == 0u) return 1.0;
  offset = max(offset, max(2.0 * shadow_texel_world(s, distance_to_light), shadow_min_offset(p)));
  vec3 relative = p + facing * offset - s.origin.xyz;
  uint face = faces == 6u ? shadow_cube_face(relative) : 0u;
  vec4 clip = s.view_proj[face] * vec4(relative, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  if (any(greaterThan(abs(ndc.xy), vec2(1.0))) || ndc.z > 1.0) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  return texture(maps, vec4(uv, layer_base + float(face), ndc.z));
}

// Most lookups per edge of a voxel's surface patch (shadow_voxel_visibility).
#define SHADOW_VOXEL_MAX_TAPS 4

// The fraction of a voxel's surface that light `s` reaches: the mean of
// shadow_surface_visibility over a grid of points on the surface's plane patch, the square of
// side `size` centred on p in the plane of unit normal `plane_normal` (p on that plane, as for
// shadow_surface_visibility). One point would decide a whole voxel wider than a shadow texel
// by wherever the averaged plane's centre falls: in a corner, a crease or under a ledge
// that point can lie in a shadow most of the surface is out of. Taps per edge: enough for
// about one per texel, at most SHADOW_VOXEL_MAX_TAPS; one where the voxel is no wider than a
// texel or has no plane (plane_normal zero).
float shadow_voxel_visibility(sampler2DArrayShadow maps, ShadowLight s, float layer_base, vec3 p,
                              vec3 plane_normal, vec3 facing, float size, float offset,
                              float distance_to_light) {
  float texel = shadow_texel_world(s, distance_to_light);
  int taps = int(clamp(ceil(size / max(texel, 1e-12)), 1.0, float(SHADOW_VOXEL_MAX_TAPS)));
  if (taps == 1 || dot(plane_normal, plane_normal) < 0.25) {
    return shadow_surface_visibility(maps, s, layer_base, p, facing, offset, distance_to_light);
  }
  vec3 t, b;
  orthonormal_basis(plane_normal, t, b);
  float sum = 0.0;
  for (int i = 0; i < taps; ++i) {
    for (int j = 0; j < taps; ++j) {
      vec2 uv = (vec2(i, j) + 0.5) / float(taps) - 0.5;
      vec3 q = p + (t * uv.x + b * uv.y) * size;
      sum += shadow_surface_visibility(maps, s, layer_base, q, facing, offset, distance_to_light);
    }
  }
  return sum / float(taps * taps);
}
#endif
