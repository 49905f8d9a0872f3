#ifndef VOXGI_VOXEL_DIRECT_LIGHT_GLSL
#define VOXGI_VOXEL_DIRECT_LIGHT_GLSL
// Contract: the light one of the scene's punctual lights sends to a point of a voxel's surface,
// shared by every pass that lights voxels (vct.inject, dvs.voxel_lighting), so that the
// families light the same voxels alike and differ only where they mean to (the cosine of
// dvs's "normal_weighted" mode, dvs's voxel-ray occlusion). No bindings of its own: the lights
// are lib/scene.glsl's (set 1). Include contracts/voxel_clipmap.glsl first.

#include "lib/common.glsl"
#include "lib/scene.glsl"

struct VoxelLightIncidence {
  vec3 direction;     // unit, from the surface point towards the light
  float attenuation;  // irradiance on a surface facing the light = light.radiance x this
  float distance;     // to a point or spot light; 0 for directional lights
};

// The light `light` at the anchor-relative point p of a voxel of edge `size`. A light inside
// the voxel (on a surface, inside geometry) lights it as if it were half a voxel away: the
// voxel's surfaces are at least that far on average, and 1/d^2 stays finite.
VoxelLightIncidence voxel_light_incidence(SceneLight light, vec3 p, float size) {
  VoxelLightIncidence incidence;
  incidence.attenuation = 1.0;
  incidence.distance = 0.0;
  if (light.type == SCENE_LIGHT_DIRECTIONAL) {
    incidence.direction = safe_normalize(-light.direction, vec3(0.0, 1.0, 0.0));
    return incidence;
  }
  vec3 to_light = voxel_relative(light.position) - p;
  float d2 = max(dot(to_light, to_light), max(0.25 * size * size, 1e-8));
  float d = sqrt(d2);
  incidence.direction = safe_normalize(to_light, vec3(0.0, 1.0, 0.0));
  incidence.attenuation = scene_light_falloff(light, d, -incidence.direction) / d2;
  incidence.distance = d;
  return incidence;
}

#endif
