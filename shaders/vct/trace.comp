#version 460
#extension GL_GOOGLE_include_directive : require
// vct.cone_trace / vct.cone_trace_specular: per pixel of the G-buffer (or per 2x2 block at
// half resolution, traced from the block's nearest pixel), cone tracing through the filtered
// volumes (contracts/cone_trace.glsl).
//   diffuse (SPECULAR 0): outgoing radiance c_diff / pi * E with E from the diffuse cones;
//                         ambient-occlusion visibility in `ao` (full res) or scratch alpha.
//                         Neighbours are averaged (interleaved sets, interleave.comp) and
//                         upsampled (half resolution) as E / pi, and each pixel multiplies by
//                         its own c_diff, so a texture's or an emitter's albedo is not blurred
//                         into the light. With interleave > 1 this dispatch writes each pixel's
//                         own gather (E / pi, a = AO; a < 0: nothing traced) for that average.
//   specular (SPECULAR 1): one cone along the reflection, aperture from GGX roughness, times
//                          the lobe's directional albedo at n.v (gbuffer_specular_weight).
// HALF 1: writes the half-resolution scratch (rgb: E / pi or the specular result, a = AO) for
// upsample.comp.
// HAS_SHADOW 1 (diffuse only): also a soft-shadow cone towards the scene's first light (seed
// 001 section 4.3): `shadow` = 1 - the cone's opacity, always at full resolution; with
// SHADOW_ONLY 1 the dispatch writes nothing else (the extra pass of resolution 'half').
#include "lib/common.glsl"
#include "lib/frame.glsl"
#ifndef HAS_FACING
#define HAS_FACING 0
#endif
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#define VCT_VOLUME_SET 0
#define VCT_VOLUME_BINDING 1
#if HAS_FACING
// The voxel normals (optional input voxel_normal): the cones' facing test.
layout(set = 0, binding = 11) uniform sampler3D facing_normals;
#define VCT_FACING_NORMALS facing_normals
#endif
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

// Workgroup edge: passes/vct/vct_pipeline.hpp kTile.
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
  int interleave;  // n of the n x n interleaved cone sets (diffuse; 1: one set everywhere)
  int lane_rows;   // VCT_LANE_ROWS_APERTURE or VCT_LANE_ROWS_CELL (contracts/cone_trace.glsl)
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
// The soft-shadow cone towards the scene's first light, stopping one voxel short of a point or
// spot light so that the light's own fixture does not shadow it. False where the visibility is
// known without a cone (`known`: 1 without lights or with the light in this voxel, 0 for
// surfaces facing away from it).
bool light_cone(vec3 world, vec3 p, vec3 n, float voxel, VctTraceSettings s, out VctCone cone,
                out float max_distance, out float known) {
  known = 1.0;
  max_distance = s.max_distance;
  if (scene_light_count() == 0u) return false;
  SceneLight light = scene_lights[0];
  vec3 l;
  float distance_to_light = s.max_distance;
  if (light.type == SCENE_LIGHT_DIRECTIONAL) {
    l = safe_normalize(-light.direction, n);
  } else {
    vec3 to_light = light.position - world;
    distance_to_light = length(to_light);
    if (!(distance_to_light > voxel)) return false;  // the light is in this voxel
    l = to_light / distance_to_light;
  }
  if (dot(n, l) <= 0.0) {
    known = 0.0;
    return false;
  }
  float offset = pc.normal_offset * voxel;
  cone = vct_cone_from_surface(p + n * offset, l, pc.shadow_tan_half_angle, n, offset);
  max_distance = min(s.max_distance, distance_to_light - voxel);
  return true;
}

#if SHADOW_ONLY
// Visibility of the scene's first light from a surface point: 1 - the opacity of its cone.
float light_visibility(vec3 world, vec3 p, vec3 n, float voxel, VctTraceSettings s) {
  VctCone cone;
  float max_distance, known;
  if (!light_cone(world, p, n, voxel, s, cone, max_distance, known)) return known;
  s.max_distance = max_distance;
  return clamp(1.0 - vct_trace_cone(cone, s).opacity, 0.0, 1.0);
}
#endif
#endif

void store_shadow(ivec2 pixel, float visibility) {
#if HAS_SHADOW
  imageStore(out_shadow, pixel, vec4(visibility));
#endif
}

#if !SPECULAR && !SHADOW_ONLY
#define INTERLEAVED 1
#else
#define INTERLEAVED 0
#endif

#if INTERLEAVED
// Interleaved cone sets (docs/vct.md): a few cones in one fixed frame see every point of a
// plane from the same few azimuths, so what they miss is missed everywhere alike (the means of
// the Cornell boxes swung by 25 points with the frame's orientation at 6 cones). Each pixel of
// an n x n window traces its own turn and ring position of the set (vct/interleave_layout.glsl),
// and its result is the average of the window over the pixels of its own surface
// (interleave.comp): n^2 cone sets at the cost of one. (Turns alone left every cone at its
// ring's middle, and a few rings sample the polar angle coarsely: 4 and 6 cones were 4 to 6
// points darker than with both on the shared Cornell box.)
#include "vct/interleave_layout.glsl"

float interleave_rotation(ivec2 pixel) {
  int n = max(pc.interleave, 1);
  return 2.0 * VCT_PI * float(vct_interleave_cell(pixel, n).x) / float(n * n);
}

float interleave_ring_position(ivec2 pixel) {
  int n = max(pc.interleave, 1);
  return (float(vct_interleave_cell(pixel, n).y) + 0.5) / float(n * n);
}

#endif

// This invocation's gather: rgb result and AO visibility in a; false where nothing was traced
// (no surface, or outside the voxel volume). Writes the shadow output itself. The diffuse
// result is E / pi, which the caller multiplies by `reflectance` after the interleaved
// average (c_diff; 1 for specular and at half resolution, where upsample.comp multiplies).
bool gather(ivec2 pixel, out GbufferSample g, out vec4 value, out vec3 reflectance) {
  value = vec4(0.0, 0.0, 0.0, 1.0);
  reflectance = vec3(1.0);
#if HALF
  ivec2 source = gbuffer_block_representative(pixel);
#else
  ivec2 source = pixel;
#endif
  g = gbuffer_sample(source);
  if (!g.valid) {
    store_shadow(pixel, 1.0);
    return false;
  }
  vec3 p = voxel_relative(g.position);
  int finest = voxel_finest_level(p, 0.0);
  if (finest < 0) {  // outside the voxel volume: nothing is known there
    store_shadow(pixel, 1.0);
    return false;
  }
  float voxel = voxel_size(finest);
  VctTraceSettings s;
  s.step_factor = pc.step_factor;
  s.max_distance = pc.max_distance;
  s.start_distance = pc.start_offset * voxel;
  s.ao_falloff = pc.ao_falloff;
  s.lanes = pc.lanes;
  s.lane_rows = pc.lane_rows;
#if SHADOW_ONLY
  store_shadow(pixel, light_visibility(g.position, p, g.normal, voxel, s));
  return false;
#elif SPECULAR
  vec3 v = safe_normalize(frame.camera_position.xyz - g.position, g.normal);
  vec3 r = reflect(-v, g.normal);
  // Shading normals can reflect below the surface: lift the cone back over the horizon.
  r = safe_normalize(r + g.normal * max(0.0, 0.02 - dot(r, g.normal)), g.normal);
  float offset = pc.normal_offset * voxel;
  VctCone cone = vct_cone_from_surface(p + g.normal * offset, r,
                                       vct_specular_tan_half_angle(g.roughness), g.normal, offset);
  VctConeResult traced = vct_trace_cone(cone, s);
  value = vec4(gbuffer_specular_weight(g) * traced.radiance, 1.0);
  return true;
#else
  // The soft-shadow cone is traced in the diffuse cones' loop, as its first: a second call
  // site of the cone tracer would double the pipeline's code (contracts/cone_trace.glsl).
  VctCone shadow_cone = vct_cone_from_surface(p, g.normal, 0.0, g.normal, 0.0);
  float shadow_max_distance = s.max_distance;
  float shadow = 1.0;
#if HAS_SHADOW
  bool trace_shadow =
      light_cone(g.position, p, g.normal, voxel, s, shadow_cone, shadow_max_distance, shadow);
#else
  const bool trace_shadow = false;
#endif
  float visibility, shadow_opacity;
  vec3 irradiance = vct_diffuse_irradiance_and_cone(
      p, g.normal, pc.diffuse_cones, interleave_rotation(pixel), interleave_ring_position(pixel),
      pc.normal_offset * voxel, s, trace_shadow, shadow_cone, shadow_max_distance, visibility,
      shadow_opacity);
  if (trace_shadow) shadow = clamp(1.0 - shadow_opacity, 0.0, 1.0);
  store_shadow(pixel, shadow);
#if !HALF
  reflectance = gbuffer_diffuse_reflectance(g);
#endif
  value = vec4(irradiance / VCT_PI, visibility);
  return true;
#endif
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (!all(lessThan(uvec2(pixel), pc.size))) return;
  GbufferSample g;
  vec4 value = vec4(0.0, 0.0, 0.0, 1.0);
  vec3 reflectance = vec3(1.0);
  bool traced = gather(pixel, g, value, reflectance);
#if INTERLEAVED
  if (pc.interleave > 1) {
    // This pixel's own cone set, for interleave.comp's average (E / pi, a = AO visibility;
    // a < 0 where nothing was traced).
    imageStore(out_result, pixel,
               traced ? vec4(sanitize_radiance(value.rgb), value.a) : vec4(0.0, 0.0, 0.0, -1.0));
    return;
  }
#endif
  store(pixel, value.rgb * reflectance, value.a);
}
