#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred voxel shading, direct part (Villegas §2): the outgoing diffuse radiance of every
// voxel of the clipmap under the scene's punctual lights (contracts/voxel_direct_light.glsl),
// with the plane's cosine or the normal-weighted attenuation of §2.1, occlusion from the
// shadow maps or from soft voxel ray casting (§2.2.1), plus the voxel's emission (§2.3). One
// invocation per texel of the stacked clipmap image. With the faces volume (HAS_FACES) each
// group of the voxel's writers (the surfaces facing along one signed axis,
// contracts/voxel_volumes.glsl) is lit on its own, with its own normal, surface point and
// occlusion, and the voxel holds their mean weighted by their share of its area.
#include "contracts/voxel_clipmap.glsl"
#include "lib/common.glsl"
#include "contracts/voxel_volumes.glsl"
#include "lib/scene.glsl"
#include "contracts/shadow_data.glsl"
#include "dvs/voxel_volume.glsl"
#include "contracts/voxel_direct_light.glsl"

#ifndef HAS_EMISSION
#define HAS_EMISSION 0
#endif
#ifndef HAS_SHADOW_MAPS
#define HAS_SHADOW_MAPS 0
#endif
#ifndef HAS_DIRECT_COPY
#define HAS_DIRECT_COPY 0
#endif
#ifndef HAS_FACES
#define HAS_FACES 0
#endif

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

// binding 0: VoxelClipmapInfo (contracts/voxel_clipmap.glsl)
layout(set = 0, binding = 1) uniform sampler3D voxel_albedo;
layout(set = 0, binding = 2) uniform sampler3D voxel_normal;
#if HAS_EMISSION
layout(set = 0, binding = 3) uniform sampler3D voxel_emission;
#endif
#if HAS_SHADOW_MAPS
layout(set = 0, binding = 4) uniform sampler2DArrayShadow shadow_maps;
layout(set = 0, binding = 5, std430) readonly buffer ShadowBlock { ShadowLight shadow_lights[]; };
#endif
layout(set = 0, binding = 6, rgba16f) writeonly uniform image3D out_radiance;
#if HAS_DIRECT_COPY
layout(set = 0, binding = 7, rgba16f) writeonly uniform image3D out_direct;
#endif
#if HAS_FACES
layout(set = 0, binding = 8) uniform usampler3D voxel_faces;
#endif
#ifndef HAS_LIGHT_SHARES
#define HAS_LIGHT_SHARES 0
#endif
#if HAS_LIGHT_SHARES
// Per face group its share of the voxel's light (contracts/voxel_volumes.glsl), for vct.filter;
// with HAS_DIRECT_COPY also kept for dvs.voxel_bounce, as the radiance is.
layout(set = 0, binding = 9, r32ui) writeonly uniform uimage3D out_light_shares;
#if HAS_DIRECT_COPY
layout(set = 0, binding = 10, r32ui) writeonly uniform uimage3D out_direct_shares;
#endif
#endif

const uint OCCLUSION_NONE = 0u;
const uint OCCLUSION_SHADOW_MAP = 1u;
const uint OCCLUSION_VOXEL_RAYS = 2u;
const uint COSINE_PLANE = 0u;
const uint COSINE_NORMAL_WEIGHTED = 1u;

layout(push_constant) uniform Push {
  uvec3 size;           // the stacked image: (R, R, R * L)
  uint occlusion;       // OCCLUSION_*
  float shadow_kappa;   // occlusion per fully opaque voxel crossed at one voxel of distance
  float shadow_bias;    // start offset of voxel shadow rays, in voxels of the receiver
  uint shadow_slots;    // lights with shadow-map data
  uint max_steps;       // cap on the samples of one shadow ray
  uint cosine;          // COSINE_*
} pc;

// §2.2.1 soft voxel shadows: march from the voxel towards the light through the opacity of
// the finest level that holds each sample, accumulating nu += (1 - nu) * kappa * alpha / t
// per voxel crossed (t in voxels of the receiver, so near occluders give hard, far ones soft
// shadows). Returns 1 - nu, the fraction of light that arrives.
float voxel_ray_visibility(vec3 origin, vec3 dir, float max_t, float receiver_size) {
  float nu = 0.0;
  float t = pc.shadow_bias * receiver_size;
  for (uint s = 0u; s < pc.max_steps && t < max_t; ++s) {
    vec3 p = origin + dir * t;
    int level = voxel_finest_level(p, 1.0);
    if (level < 0) break;  // the ray left the volume
    float size = voxel_size(level);
    float alpha = dvs_opacity(voxel_albedo, p, level);
    const float step_voxels = 0.5;
    float gain = pc.shadow_kappa * alpha * step_voxels * (size / receiver_size) /
                 max(t / receiver_size, 1.0);
    nu += (1.0 - nu) * clamp(gain, 0.0, 1.0);
    if (nu >= 0.999) return 0.0;
    t += step_voxels * size;
  }
  return 1.0 - nu;
}


// D(N, l): the cosine of a surface with normal `normal` (the voxel's averaged normal, any
// length, or one group's unit normal) towards the unit light direction l. Mode "plane": the
// surface is the plane of that normal, D = max(N.l, 0), what a surface receives. Mode
// "normal_weighted": the seed's attenuation (§2.1), which lights the voxel as the axis faces its
// normal selects; for a tilted plane it differs from the plane's cosine, and it lights planes
// turned away from a grazing light (docs/dvs.md). Where the faces cancelled both use the
// seed's third per axis, half lit.
float surface_cosine(vec3 normal, vec3 l) {
  float len2 = dot(normal, normal);
  if (pc.cosine == COSINE_NORMAL_WEIGHTED || !(len2 >= 1e-6) || isinf(len2)) {
    return dvs_normal_weighted_cosine(normal, l);
  }
  return max(dot(normal * inversesqrt(len2), l), 0.0);
}

// Irradiance at the point p (anchor-relative) of a surface with normal `normal` (the voxel's
// averaged normal, any length, or one group's unit normal) in a voxel of edge `size`.
vec3 surface_irradiance(vec3 p, vec3 normal, float size) {
  vec3 n = safe_normalize(normal, vec3(0.0));
  vec3 irradiance = vec3(0.0);
  uint light_count = scene_light_count();
  for (uint i = 0u; i < light_count; ++i) {
    SceneLight light = scene_lights[i];
    VoxelLightIncidence incidence = voxel_light_incidence(light, p, size);
    vec3 l = incidence.direction;
    float cosine = surface_cosine(normal, l);
    if (incidence.attenuation <= 0.0 || cosine <= 0.0) continue;
    float visibility = 1.0;
    // Rays and lookups start off the surface: along the normal, or towards the light where
    // the faces cancelled.
    vec3 offset_dir = dot(n, n) > 0.0 ? n : l;
    if (pc.occlusion == OCCLUSION_VOXEL_RAYS) {
      vec3 origin = p + offset_dir * (pc.shadow_bias * size);
      // Directional lights: no end; point lights: up to half a voxel before the light.
      float max_t = incidence.distance > 0.0 ? incidence.distance - 0.5 * size : 3.4e38;
      visibility = voxel_ray_visibility(origin, l, max_t, size);
    }
#if HAS_SHADOW_MAPS
    if (pc.occlusion == OCCLUSION_SHADOW_MAP && i < pc.shadow_slots) {
      // Over the voxel's surface patch, each point off the surface by two shadow-map texels
      // (contracts/shadow_data.glsl); the voxel-ray start offset would look past occluders
      // close in front of the surface.
      visibility =
          shadow_voxel_visibility(shadow_maps, shadow_lights[i], float(i * 6u),
                                  p + voxel_clipmap.anchor.xyz, n, offset_dir, size, 0.0,
                                  incidence.distance);
    }
#endif
    irradiance += light.radiance * (incidence.attenuation * cosine * visibility);
  }
  return irradiance;
}

void main() {
  ivec3 texel = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(uvec3(texel), pc.size))) return;
  int level = dvs_texel_level(texel);
  vec4 albedo = texelFetch(voxel_albedo, texel, 0);
  vec4 normal = texelFetch(voxel_normal, texel, 0);
  vec3 radiance = vec3(0.0);
#if HAS_EMISSION
  radiance += sanitize_radiance(texelFetch(voxel_emission, texel, 0).rgb);
#endif
  vec3 emission = radiance;
  uint light_shares = 0u;
  bool occupied = albedo.a > 0.0 || normal.w > 0.0;
  if (occupied && voxel_level_valid(level)) {
    float size = voxel_size(level);
    // Lit on its average surface plane, not at its centre (contracts/voxel_volumes.glsl).
    vec3 center = dvs_texel_center(texel, level);
    float offset = voxel_plane_offset(normal) * size;
    // Each way the voxel's surfaces face lit as a plane of its own, weighted by its area
    // share; or the voxel as one plane.
    vec3 irradiance = vec3(0.0);
    int groups = 0;
#if HAS_FACES
    // Each group from its own frontmost plane; and its light (luminance x area share), for
    // the light shares.
    vec3 face_normals[VOXEL_FACE_GROUPS];
    float face_shares[VOXEL_FACE_GROUPS], face_offsets[VOXEL_FACE_GROUPS];
    groups = voxel_faces_unpack(texelFetch(voxel_faces, texel, 0), face_normals, face_shares,
                                face_offsets);
    float group_light[VOXEL_FACE_GROUPS];
    for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
      group_light[g] = 0.0;
      if (face_shares[g] <= 0.0) continue;
      vec3 p = center + face_normals[g] * (face_offsets[g] * size);
      vec3 e = surface_irradiance(p, face_normals[g], size);
      irradiance += face_shares[g] * e;
      group_light[g] = face_shares[g] *
                       voxel_luminance(albedo.rgb * (1.0 / 3.14159265358979) * e + emission);
    }
    light_shares = voxel_pack_light_shares(group_light);
#endif
    if (groups == 0) {  // no faces volume, or a voxel written without one
      vec3 n = safe_normalize(normal.xyz, vec3(0.0));
      irradiance = surface_irradiance(center + n * offset, normal.xyz, size);
    }
    radiance += albedo.rgb * (1.0 / 3.14159265358979) * irradiance;
  }
  vec4 result = vec4(sanitize_radiance(radiance), clamp(albedo.a, 0.0, 1.0));
  imageStore(out_radiance, texel, result);
#if HAS_DIRECT_COPY
  imageStore(out_direct, texel, result);
#endif
#if HAS_LIGHT_SHARES
  imageStore(out_light_shares, texel, uvec4(light_shares));
#if HAS_DIRECT_COPY
  imageStore(out_direct_shares, texel, uvec4(light_shares));
#endif
#endif
}
