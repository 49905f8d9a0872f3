#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred voxel shading, one indirect bounce per voxel (Villegas, "Voxel Global
// Illumination"): diffuse cones over the hemisphere of each voxel's averaged normal gather the
// irradiance E from the filtered radiance volume (vct.filter's output, contracts/cone_trace.glsl),
// and the voxel's outgoing radiance becomes direct + albedo / pi * E. Repeated K times, each
// time after filtering, this is the fixed-point iteration L = L_direct + albedo/pi * E[L], a
// contraction with gain at most albedo < 1 (docs/dvs.md).
#include "contracts/voxel_volumes.glsl"
#include "contracts/voxel_clipmap.glsl"
#define VCT_VOLUME_SET 0
#define VCT_VOLUME_BINDING 1
// The voxel normals, bound with the volumes' sampler (texelFetch ignores it): read per voxel
// below, and interpolated by the cones' facing test.
layout(set = 0, binding = 3) uniform sampler3D voxel_normal;
#define VCT_FACING_NORMALS voxel_normal
#include "contracts/cone_trace.glsl"
#include "lib/common.glsl"
#include "dvs/voxel_volume.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

// binding 0: VoxelClipmapInfo; binding 1: vct_volumes (contracts/cone_trace.glsl)
layout(set = 0, binding = 2) uniform sampler3D voxel_albedo;
layout(set = 0, binding = 4) uniform sampler3D direct_radiance;
layout(set = 0, binding = 5, rgba16f) writeonly uniform image3D out_radiance;
#ifndef HAS_LIGHT_SHARES
#define HAS_LIGHT_SHARES 0
#endif
#if HAS_LIGHT_SHARES
// The voxels' face groups, the direct light's shares among them, and the shares of the light
// written here (contracts/voxel_volumes.glsl), for vct.filter: the direct light keeps its
// shares, the bounce, gathered around the voxel's mean normal, goes to the groups by area.
layout(set = 0, binding = 6) uniform usampler3D voxel_faces;
layout(set = 0, binding = 7) uniform usampler3D direct_shares;
layout(set = 0, binding = 8, r32ui) writeonly uniform uimage3D out_light_shares;
#endif

layout(push_constant) uniform Push {
  uvec3 size;  // the stacked image: (R, R, R * L)
  int cones;
  float step_factor;
  float max_distance;   // scene units (FLT_MAX: no limit)
  float normal_offset;  // voxels of the voxel's level
  float start_offset;   // voxels of the voxel's level
} pc;

// Each voxel's own turn (radians) and ring position of its cone set (vct_diffuse_cone), from
// an R3 low-discrepancy sequence over its texel, so that neighbouring voxels look along
// different directions and the final gather, which averages many voxels, averages their sets.
// A texel holds the same world voxel however the window moves (toroidal addressing), so a
// voxel's set stays put. (One set for every voxel aimed every plane's cones the same way: with
// 4 cones the Cornell boxes' second bounce read 1.22-1.33x the path tracer's on the ceiling and
// 0.50-0.57x on the blocks' fronts; docs/error-budget.md, forty-first round.)
vec2 voxel_cone_set(ivec3 texel) {
  const vec3 r3 = vec3(0.8191725134, 0.6710436067, 0.5497004779);  // 1 / phi3^(1, 2, 3)
  float u = fract(0.5 + dot(vec3(texel), r3));
  float v = fract(0.5 + dot(vec3(texel), r3.yzx));
  return vec2(2.0 * VCT_PI * u, v);
}

void main() {
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(uvec3(texel), pc.size))) return;
  int level = dvs_texel_level(texel);
  vec4 direct = texelFetch(direct_radiance, texel, 0);
  vec3 radiance = sanitize_radiance(direct.rgb);
  vec3 bounce = vec3(0.0);
  float opacity = isnan(direct.a) ? 0.0 : clamp(direct.a, 0.0, 1.0);
  vec4 albedo = texelFetch(voxel_albedo, texel, 0);
  vec3 n = texelFetch(voxel_normal, texel, 0).xyz;
  float n_len2 = dot(n, n);
  bool occupied = albedo.a > 0.0 && any(greaterThan(albedo.rgb, vec3(0.0)));
  // Faces that cancelled (a thin wall) leave no facing to gather around; gathering both sides
  // would carry light through the wall, so such voxels keep their direct light only.
  bool has_normal = n_len2 >= 1e-6 && !isinf(n_len2);
  if (occupied && has_normal && voxel_level_valid(level)) {
    float size = voxel_size(level);
    vec3 p = dvs_texel_center(texel, level);
    // Where a finer level covers this voxel, vct.filter replaces it by the finer data: no
    // need to gather here.
    bool covered = level > 0 && voxel_inside_window(voxel_window_coord(p, level - 1));
    if (!covered) {
      VctTraceSettings s;
      s.step_factor = pc.step_factor;
      s.max_distance = pc.max_distance;
      s.start_distance = pc.start_offset * size;
      s.ao_falloff = 0.0;
      // One lane: the pixels' final gather integrates over many voxels and filters what one
      // voxel's gather aliases, at a quarter of the cost.
      s.lanes = 1;
      s.lane_rows = VCT_LANE_ROWS_APERTURE;
      float visibility;
      // Gather from the voxel's average surface plane (contracts/voxel_volumes.glsl), with the cone
      // origin normal_offset voxels off the centre as before.
      vec3 unit_n = n * inversesqrt(n_len2);
      float plane = voxel_plane_offset(texelFetch(voxel_normal, texel, 0));
      vec3 surface = p + unit_n * (plane * size);
      vec2 cone_set = voxel_cone_set(texel);
      vec3 irradiance = vct_diffuse_irradiance(surface, unit_n, pc.cones, cone_set.x, cone_set.y,
                                               (pc.normal_offset - plane) * size, s, visibility);
      bounce = albedo.rgb * (1.0 / VCT_PI) * sanitize_radiance(irradiance);
      radiance += bounce;
    }
  }
  imageStore(out_radiance, texel, vec4(sanitize_radiance(radiance), opacity));
#if HAS_LIGHT_SHARES
  vec3 normals[VOXEL_FACE_GROUPS];
  float area[VOXEL_FACE_GROUPS], direct_share[VOXEL_FACE_GROUPS];
  voxel_faces_unpack(texelFetch(voxel_faces, texel, 0), normals, area);
  bool lit = voxel_light_shares_unpack(texelFetch(direct_shares, texel, 0).r, direct_share);
  float direct_light = voxel_luminance(radiance - bounce), bounce_light = voxel_luminance(bounce);
  float group_light[VOXEL_FACE_GROUPS];
  for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
    group_light[g] = (lit ? direct_share[g] : area[g]) * direct_light + area[g] * bounce_light;
  }
  imageStore(out_light_shares, texel, uvec4(voxel_pack_light_shares(group_light)));
#endif
}
