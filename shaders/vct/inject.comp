#version 460
#extension GL_GOOGLE_include_directive : require
// vct.inject: direct light into the radiance clipmap. For every occupied voxel of every level:
//   L_out = albedo / pi * sum_lights(E_light * cos * visibility) + emission
// the outgoing Lambert radiance of the voxel (isotropic), a = opacity (albedo alpha), with the
// light evaluated on the voxel's average surface plane, not at its centre. The shadow maps
// decide visibility, averaged over the voxel's patch of that plane where the voxel is wider
// than a shadow texel (contracts/shadow_data.glsl); cos uses the voxel's averaged normal. A
// voxel whose normal is missing or whose faces cancelled (|n| < VOXEL_NORMAL_MIN_LENGTH) is
// treated as facing each light (cos = 1): a thin wall lit from one side glows rather than
// going black, and the shadow map still decides whether light reaches it. Output is
// sanitized HDR. With the faces volume (HAS_FACES) each group of the voxel's writers
// (contracts/voxel_volumes.glsl: the surfaces that face along one signed axis) is lit as a
// plane of its own, with its normal, its visibility seen from just in front of its frontmost
// surface (so a column's or a vault's curve does not put the lookup inside it), and the voxel
// holds their mean weighted by their share of its surfaces' area: a voxel holding a sunlit
// floor and a wall turned away is not lit as one plane with their mean normal
// (docs/voxelization.md).
#include "lib/common.glsl"
#include "contracts/voxel_volumes.glsl"
#include "lib/scene.glsl"
#include "contracts/shadow_data.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#include "contracts/voxel_direct_light.glsl"

#ifndef HAS_SHADOWS
#define HAS_SHADOWS 0
#endif
#ifndef HAS_EMISSION
#define HAS_EMISSION 0
#endif
#ifndef HAS_FACES
#define HAS_FACES 0
#endif

const float INJECT_PI = 3.14159265358979323846;

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(set = 0, binding = 1) uniform sampler3D voxel_albedo;
layout(set = 0, binding = 2) uniform sampler3D voxel_normal;
#if HAS_EMISSION
layout(set = 0, binding = 3) uniform sampler3D voxel_emission;
#endif
#if HAS_SHADOWS
layout(set = 0, binding = 4) uniform sampler2DArrayShadow shadow_maps;
layout(set = 0, binding = 5, std430) readonly buffer ShadowBlock { ShadowLight shadow_lights[]; };
#endif
layout(set = 0, binding = 6, rgba16f) writeonly uniform image3D out_radiance;
#if HAS_FACES
layout(set = 0, binding = 7) uniform usampler3D voxel_faces;
#endif
#ifndef HAS_LIGHT_SHARES
#define HAS_LIGHT_SHARES 0
#endif
#if HAS_LIGHT_SHARES
layout(set = 0, binding = 8, r32ui) writeonly uniform uimage3D out_light_shares;
#endif

layout(push_constant) uniform Push {
  uint shadow_slots;    // lights with shadow data
  float normal_offset;  // shadow lookup offset, in voxels
  uint shadows_enabled;
  float pad;
} pc;

#if HAS_SHADOWS
// Visibility of the surface point p (world space) from light `index`: contracts/shadow_data.glsl.
float shadow_visibility(uint index, vec3 p, vec3 plane_normal, vec3 facing, float size,
                        float offset, float distance_to_light) {
  if (pc.shadows_enabled == 0u || index >= pc.shadow_slots) return 1.0;
  return shadow_voxel_visibility(shadow_maps, shadow_lights[index], float(index * 6u), p,
                                 plane_normal, facing, size, offset, distance_to_light);
}
#endif

// Irradiance at the anchor-relative surface point p of a plane with unit normal n (has_normal
// false: a voxel whose faces cancelled, lit as if facing each light).
vec3 surface_irradiance(vec3 p, vec3 n, bool has_normal, float size) {
  vec3 irradiance = vec3(0.0);
  uint light_count = scene_light_count();
  for (uint i = 0u; i < light_count; ++i) {
    SceneLight light = scene_lights[i];
    VoxelLightIncidence incidence = voxel_light_incidence(light, p, size);
    vec3 l = incidence.direction;
    float cos_theta = has_normal ? dot(n, l) : 1.0;
    if (incidence.attenuation <= 0.0 || cos_theta <= 0.0) continue;
    float visibility = 1.0;
#if HAS_SHADOWS
    // Look up from just in front of the surface: p lies on the group's frontmost plane (the
    // voxel's average surface plane without faces), so a small offset suffices, and a larger
    // one would look past occluders lying close in front of the surface (a lamp's shade just
    // under a ceiling).
    vec3 facing = has_normal ? n : l;
    visibility = shadow_visibility(i, p + voxel_clipmap.anchor.xyz, n, facing, size,
                                   pc.normal_offset * size, incidence.distance);
#endif
    irradiance += light.radiance * (incidence.attenuation * cos_theta * visibility);
  }
  return irradiance;
}

void main() {
  int r = voxel_resolution();
  int levels = voxel_level_count();
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(id, ivec3(r, r, r * levels)))) return;
  int level = id.z / r;
  ivec3 window = ivec3(id.xy, id.z - level * r);
  ivec3 texel = voxel_texel(window, level);
#if HAS_LIGHT_SHARES
  imageStore(out_light_shares, texel, uvec4(0u));
#endif
  if (!voxel_level_valid(level)) {
    imageStore(out_radiance, texel, vec4(0.0));
    return;
  }
  vec4 albedo = texelFetch(voxel_albedo, texel, 0);
  float opacity = clamp(isnan(albedo.a) ? 0.0 : albedo.a, 0.0, 1.0);
  vec3 emission = vec3(0.0);
#if HAS_EMISSION
  emission = sanitize_radiance(texelFetch(voxel_emission, texel, 0).rgb);
#endif
  if (opacity <= 0.0) {
    imageStore(out_radiance, texel, vec4(0.0));
    return;
  }
  vec3 reflectance = clamp(albedo.rgb, vec3(0.0), vec3(1.0)) / INJECT_PI;
  vec4 normal_occupied = texelFetch(voxel_normal, texel, 0);
  vec3 n_raw = normal_occupied.xyz;
  if (any(isnan(n_raw)) || any(isinf(n_raw))) n_raw = vec3(0.0);
  float n_len = length(n_raw);
  bool has_normal = n_len >= VOXEL_NORMAL_MIN_LENGTH;
  vec3 n = has_normal ? n_raw / n_len : vec3(0.0);

  // The voxel's surface: its centre moved onto the average surface plane
  // (contracts/voxel_volumes.glsl), anchor-relative.
  float size = voxel_size(level);
  vec3 center = voxel_level_min(level) + (vec3(window) + 0.5) * size;
  float offset = voxel_plane_offset(normal_occupied) * size;
  // Each way the voxel's surfaces face lit as a plane of its own, weighted by its area share;
  // or the voxel as one plane.
  vec3 irradiance = vec3(0.0);
  int groups = 0;
#if HAS_FACES
  vec3 face_normals[VOXEL_FACE_GROUPS];
  float face_shares[VOXEL_FACE_GROUPS], face_offsets[VOXEL_FACE_GROUPS];
  groups = voxel_faces_unpack(texelFetch(voxel_faces, texel, 0), face_normals, face_shares,
                              face_offsets);
  // Each group's light (luminance x area share), for the light shares.
  float group_light[VOXEL_FACE_GROUPS];
  for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
    group_light[g] = 0.0;
    if (face_shares[g] <= 0.0) continue;
    vec3 p = center + face_normals[g] * (face_offsets[g] * size);
    vec3 e = surface_irradiance(p, face_normals[g], true, size);
    irradiance += face_shares[g] * e;
    group_light[g] = face_shares[g] * voxel_luminance(reflectance * e + emission);
  }
#if HAS_LIGHT_SHARES
  imageStore(out_light_shares, texel, uvec4(voxel_pack_light_shares(group_light)));
#endif
#endif
  if (groups == 0) {  // no faces volume, or a voxel written without one
    vec3 p = center + (has_normal ? n * offset : vec3(0.0));
    irradiance = surface_irradiance(p, n, has_normal, size);
  }
  vec3 radiance = reflectance * irradiance + emission;
  imageStore(out_radiance, texel, vec4(sanitize_radiance(radiance), opacity));
}
