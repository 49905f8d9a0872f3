#version 460
#extension GL_GOOGLE_include_directive : require
// vct.cone_trace / vct.cone_trace_specular: per pixel of the G-buffer (or per 2x2 block at
// half resolution, traced from the block's nearest pixel), cone tracing through the filtered
// volumes (contracts/cone_trace.glsl).
//   diffuse (SPECULAR 0): outgoing radiance c_diff / pi * E with E from the diffuse cones;
//                         ambient-occlusion visibility in `ao` (full res) or scratch alpha.
//   specular (SPECULAR 1): one cone along the reflection, aperture from GGX roughness, times
//                          Schlick's Fresnel at n.v.
// HALF 1: writes the half-resolution scratch (rgb result, a = AO) for upsample.comp.
// HAS_SHADOW 1 (diffuse only): also a soft-shadow cone towards the scene's first light (seed
// 001 section 4.3): `shadow` = 1 - the cone's opacity, always at full resolution; with
// SHADOW_ONLY 1 the dispatch writes nothing else (the extra pass of resolution 'half').
#include "lib/common.glsl"
#include "lib/frame.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#define VCT_VOLUME_SET 0
#define VCT_VOLUME_BINDING 1
#include "contracts/cone_trace.glsl"
#include "vct/gbuffer_sample.glsl"

#ifndef SPECULAR
#define SPECULAR 0
#endif
#ifndef HALF
#define HALF 0
#endif
#ifndef HAS_AO
#define HAS_AO 0
#endif
#ifndef AO_FORMAT
#define AO_FORMAT r16f
#endif
#ifndef HAS_SHADOW
#define HAS_SHADOW 0
#endif
#ifndef SHADOW_ONLY
#define SHADOW_ONLY 0
#endif
#ifndef SHADOW_FORMAT
#define SHADOW_FORMAT r16f
#endif

layout(local_size_x = 8, local_size_y = 8) in;

#if !SHADOW_ONLY
layout(set = 0, binding = 7, rgba16f) writeonly uniform image2D out_result;
#endif
#if HAS_AO && !HALF && !SHADOW_ONLY
layout(set = 0, binding = 8, AO_FORMAT) writeonly uniform image2D out_ao;
#endif
#if HAS_SHADOW
#include "lib/scene.glsl"
layout(set = 0, binding = 10, SHADOW_FORMAT) writeonly uniform image2D out_shadow;
#endif

layout(push_constant) uniform Push {
  uvec2 size;  // of out_result
  int diffuse_cones;
  float step_factor;
  float max_distance;
  float ao_falloff;
  float normal_offset;  // in voxels of the finest level containing the point
  float start_offset;   // in voxels
  float shadow_tan_half_angle;
  int lanes;  // of a capped cone (contracts/cone_trace.glsl)
} pc;

void store(ivec2 pixel, vec3 result, float visibility) {
#if !SHADOW_ONLY
  imageStore(out_result, pixel, vec4(sanitize_radiance(result), HALF != 0 ? visibility : 1.0));
#endif
#if HAS_AO && !HALF && !SHADOW_ONLY
  imageStore(out_ao, pixel, vec4(visibility));
#endif
}

#if HAS_SHADOW
// Visibility of the scene's first light from a surface point: 1 - the opacity of a cone
// towards it (1 without lights; 0 for surfaces facing away from it). The cone stops one voxel
// short of a point or spot light, so the light's own fixture does not shadow it.
float light_visibility(vec3 world, vec3 p, vec3 n, float voxel, VctTraceSettings s) {
  if (scene_light_count() == 0u) return 1.0;
  SceneLight light = scene_lights[0];
  vec3 l;
  float distance_to_light = s.max_distance;
  if (light.type == SCENE_LIGHT_DIRECTIONAL) {
    l = safe_normalize(-light.direction, n);
  } else {
    vec3 to_light = light.position - world;
    distance_to_light = length(to_light);
    if (!(distance_to_light > voxel)) return 1.0;  // the light is in this voxel
    l = to_light / distance_to_light;
  }
  if (dot(n, l) <= 0.0) return 0.0;
  float offset = pc.normal_offset * voxel;
  VctCone cone = vct_cone_from_surface(p + n * offset, l, pc.shadow_tan_half_angle, n, offset);
  s.max_distance = min(s.max_distance, distance_to_light - voxel);
  return clamp(1.0 - vct_trace_cone(cone, s).opacity, 0.0, 1.0);
}
#endif

void store_shadow(ivec2 pixel, float visibility) {
#if HAS_SHADOW
  imageStore(out_shadow, pixel, vec4(visibility));
#endif
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.size))) return;
#if HALF
  ivec2 source = gbuffer_block_representative(pixel);
#else
  ivec2 source = pixel;
#endif
  GbufferSample g = gbuffer_sample(source);
  if (!g.valid) {
    store(pixel, vec3(0.0), 1.0);
    store_shadow(pixel, 1.0);
    return;
  }
  vec3 p = voxel_relative(g.position);
  int finest = voxel_finest_level(p, 0.0);
  if (finest < 0) {  // outside the voxel volume: nothing is known there
    store(pixel, vec3(0.0), 1.0);
    store_shadow(pixel, 1.0);
    return;
  }
  float voxel = voxel_size(finest);
  VctTraceSettings s;
  s.step_factor = pc.step_factor;
  s.max_distance = pc.max_distance;
  s.start_distance = pc.start_offset * voxel;
  s.ao_falloff = pc.ao_falloff;
  s.lanes = pc.lanes;
#if HAS_SHADOW
  store_shadow(pixel, light_visibility(g.position, p, g.normal, voxel, s));
#endif
#if SHADOW_ONLY
  return;
#endif
#if SPECULAR
  vec3 v = safe_normalize(frame.camera_position.xyz - g.position, g.normal);
  vec3 r = reflect(-v, g.normal);
  // Shading normals can reflect below the surface: lift the cone back over the horizon.
  r = safe_normalize(r + g.normal * max(0.0, 0.02 - dot(r, g.normal)), g.normal);
  float offset = pc.normal_offset * voxel;
  VctCone cone = vct_cone_from_surface(p + g.normal * offset, r,
                                       vct_specular_tan_half_angle(g.roughness), g.normal, offset);
  VctConeResult traced = vct_trace_cone(cone, s);
  vec3 f0 = mix(vec3(0.04), g.base_color, g.metallic);
  float n_dot_v = clamp(dot(g.normal, v), 0.0, 1.0);
  float m = 1.0 - n_dot_v;
  vec3 fresnel = f0 + (vec3(1.0) - f0) * (m * m * m * m * m);
  store(pixel, fresnel * traced.radiance, 1.0);
#else
  float visibility;
  vec3 irradiance =
      vct_diffuse_irradiance(p, g.normal, pc.diffuse_cones, pc.normal_offset * voxel, s, visibility);
  vec3 c_diff = g.base_color * (1.0 - g.metallic);
  store(pixel, c_diff / VCT_PI * irradiance, visibility);
#endif
}
