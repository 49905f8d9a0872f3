#ifndef VOXGI_COMMON_GLSL
#define VOXGI_COMMON_GLSL
// Small numeric helpers shared by all shaders.

const float HALF_MAX = 65504.0;

// Values written to 16-bit float targets: finite, non-negative and below the half maximum, so
// that one bad value can never turn into Inf or NaN downstream.
vec3 sanitize_radiance(vec3 c) {
  bvec3 bad = bvec3(isnan(c.x) || isinf(c.x), isnan(c.y) || isinf(c.y), isnan(c.z) || isinf(c.z));
  c = mix(c, vec3(0.0), bad);
  return clamp(c, vec3(0.0), vec3(HALF_MAX));
}

vec3 safe_normalize(vec3 v, vec3 fallback) {
  float len2 = dot(v, v);
  return len2 > 1e-20 ? v * inversesqrt(len2) : fallback;
}

// World position of a pixel from its depth (Vulkan clip space, depth 0..1). Goes through view
// space (inverse projection, then inverse view) rather than one inverse view-projection: that
// product loses float precision when the scene is far from the origin.
vec3 reconstruct_world_position(mat4 inv_proj, mat4 inv_view, vec2 uv, float depth) {
  vec4 view = inv_proj * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return (inv_view * vec4(view.xyz / view.w, 1.0)).xyz;
}

#endif
