#version 460
#extension GL_GOOGLE_include_directive : require
// Deferred direct lighting: glTF BRDF × punctual lights (KHR_lights_punctual), shadowed by
// the shadow maps (PCF), plus emission.
#include "lib/frame.glsl"
#include "lib/common.glsl"
#include "lib/brdf.glsl"
#include "lib/scene.glsl"
#include "contracts/shadow_data.glsl"
#include "contracts/gbuffer.glsl"

#ifndef HAS_SHADOWS
#define HAS_SHADOWS 0
#endif

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 1) uniform sampler2D g_base_color;
layout(set = 0, binding = 2) uniform sampler2D g_normal;
layout(set = 0, binding = 3) uniform sampler2D g_material;
layout(set = 0, binding = 4) uniform sampler2D g_emission;
layout(set = 0, binding = 5) uniform sampler2D g_depth;
#if HAS_SHADOWS
layout(set = 0, binding = 6) uniform sampler2DArrayShadow shadow_maps;
layout(set = 0, binding = 7, std430) readonly buffer ShadowBlock { ShadowLight shadow_lights[]; };
#endif
layout(set = 0, binding = 8) writeonly uniform image2D out_radiance;

layout(push_constant) uniform Push {
  uvec2 size;
  uint shadow_slots;
  uint shadows_enabled;
  float normal_bias;
  int pcf_radius;
  float background;
  float pad;
} pc;

#if HAS_SHADOWS
// Fraction of the light that reaches p (1 = lit), percentage-closer filtered.
float shadow_visibility(uint light_index, vec3 p, vec3 n, float distance_to_light) {
  if (pc.shadows_enabled == 0u || light_index >= pc.shadow_slots) return 1.0;
  ShadowLight s = shadow_lights[light_index];
  uint faces = uint(s.info.x + 0.5);
  if (faces == 0u) return 1.0;
  float texel_world = shadow_texel_world(s, distance_to_light);
  vec3 biased = p + n * max(pc.normal_bias * texel_world, shadow_min_offset(p));
  vec3 relative = biased - s.origin.xyz;
  uint face = faces == 6u ? shadow_cube_face(relative) : 0u;
  vec4 clip = s.view_proj[face] * vec4(relative, 1.0);
  if (clip.w <= 0.0) return 1.0;
  vec3 ndc = clip.xyz / clip.w;
  if (any(greaterThan(abs(ndc.xy), vec2(1.0))) || ndc.z > 1.0) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  float layer = float(light_index * 6u + face);
  vec2 texel = 1.0 / vec2(textureSize(shadow_maps, 0).xy);
  float sum = 0.0;
  int taps = 0;
  for (int dy = -pc.pcf_radius; dy <= pc.pcf_radius; ++dy) {
    for (int dx = -pc.pcf_radius; dx <= pc.pcf_radius; ++dx) {
      sum += texture(shadow_maps, vec4(uv + vec2(dx, dy) * texel, layer, ndc.z));
      ++taps;
    }
  }
  return sum / float(taps);
}
#endif

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.size))) return;
  float depth = texelFetch(g_depth, pixel, 0).r;
  if (!gbuffer_has_surface(depth)) {
    imageStore(out_radiance, pixel, vec4(vec3(pc.background), 1.0));
    return;
  }
  vec2 uv = (vec2(pixel) + 0.5) / vec2(pc.size);
  vec3 p = reconstruct_world_position(frame.inv_proj, frame.inv_view, uv, depth);
  vec4 normal_roughness = texelFetch(g_normal, pixel, 0);
  vec3 n = gbuffer_normal(normal_roughness);
  SurfaceBrdf surface;
  surface.base_color = gbuffer_base_color(texelFetch(g_base_color, pixel, 0));
  surface.metallic = gbuffer_metallic(texelFetch(g_material, pixel, 0));
  surface.roughness = gbuffer_roughness(normal_roughness);
  vec3 v = safe_normalize(frame.camera_position.xyz - p, n);

  vec3 radiance = gbuffer_emission(texelFetch(g_emission, pixel, 0));
  uint light_count = scene_light_count();
  for (uint i = 0u; i < light_count; ++i) {
    SceneLight light = scene_lights[i];
    vec3 l;
    float attenuation = 1.0;
    float distance_to_light = 0.0;
    if (light.type == SCENE_LIGHT_DIRECTIONAL) {
      l = safe_normalize(-light.direction, vec3(0.0, 1.0, 0.0));
    } else {
      vec3 to_light = light.position - p;
      // A light on (or in) a surface must not give 1/0: distances below 0.1 mm are clamped.
      float d2 = max(dot(to_light, to_light), 1e-8);
      distance_to_light = sqrt(d2);
      l = to_light / distance_to_light;
      attenuation = scene_light_falloff(light, distance_to_light, -l) / d2;
    }
    if (attenuation <= 0.0 || dot(n, l) <= 0.0) continue;
    float visibility = 1.0;
#if HAS_SHADOWS
    visibility = shadow_visibility(i, p, n, distance_to_light);
#endif
    radiance += gltf_brdf_cos(surface, n, v, l) * light.radiance * (attenuation * visibility);
  }
  imageStore(out_radiance, pixel, vec4(sanitize_radiance(radiance), 1.0));
}
