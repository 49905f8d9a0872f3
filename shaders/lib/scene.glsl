#ifndef VOXGI_SCENE_GLSL
#define VOXGI_SCENE_GLSL
// Descriptor set 1 of scene-drawing pipelines (voxgi::scene::GpuScene) and material sampling.
// The std430 structs mirror GpuMaterial, GpuInstance and GpuLight in
// engine/scene/gpu_scene.hpp; keep them in step.
//
// Textures are layers of two array textures (sRGB and linear), so a material index may differ
// per pixel without descriptor indexing. Shaders outside the fragment stage have no implicit
// derivatives: define SCENE_TEXTURE_EXPLICIT_LOD before including this file, and the textures
// are sampled at mip level scene_texture_lod (default 0).

struct SceneMaterial {
  vec4 base_color;
  vec3 emissive;
  float metallic;
  float roughness;
  float normal_scale;
  float occlusion_strength;
  float alpha_cutoff;
  int base_color_tex;  // layer in scene_textures_srgb; -1: none
  int metallic_roughness_tex;  // layer in scene_textures_linear
  int normal_tex;              // layer in scene_textures_linear
  int occlusion_tex;           // layer in scene_textures_linear
  int emissive_tex;            // layer in scene_textures_srgb
  uint alpha_mode;  // SCENE_ALPHA_*
  uint double_sided;
  uint clamp_mask;  // bit per slot (base, metallic-roughness, normal, occlusion, emissive)
  // Per slot two rows of its texture-coordinate transform; uv_rows[2 * slot].w is its TEXCOORD set.
  vec4 uv_rows[10];
};

// What a surface point's vertices give material sampling besides the normal and tangent.
struct SurfaceAttributes {
  vec2 uv0;    // TEXCOORD_0
  vec2 uv1;    // TEXCOORD_1 (the loader copies set 0 where a mesh has no set 1)
  vec4 color;  // COLOR_0, linear RGBA; (1, 1, 1, 1) without one
};

const uint SCENE_ALPHA_OPAQUE = 0u;
const uint SCENE_ALPHA_MASK = 1u;
const uint SCENE_ALPHA_BLEND = 2u;

// SceneInstance.flags: the world matrix mirrors (negative determinant). The draw already uses
// winding-swapped indices; only the tangent handedness needs the flip (scene_world_tangent).
const uint SCENE_INSTANCE_MIRRORED = 1u;

struct SceneInstance {
  mat4 world;
  mat4 normal_matrix;  // inverse transpose of world
  uint material;
  uint flags;
  uint pad0;
  uint pad1;
};

const uint SCENE_LIGHT_DIRECTIONAL = 0u;
const uint SCENE_LIGHT_POINT = 1u;
const uint SCENE_LIGHT_SPOT = 2u;

struct SceneLight {
  vec3 position;
  uint type;       // SCENE_LIGHT_*
  vec3 direction;  // where the light points
  float range;     // 0 = infinite
  vec3 radiance;   // color × intensity (cd for point/spot, lux for directional)
  float spot_scale;   // cone: clamp(cos_angle * spot_scale + spot_offset, 0, 1)^2
  float spot_offset;  // (point and directional: scale 0, offset 1)
  int shadow_index;
  float pad0;
  float pad1;
};

layout(set = 1, binding = 0, std430) readonly buffer SceneMaterials {
  SceneMaterial scene_materials[];
};
layout(set = 1, binding = 1, std430) readonly buffer SceneInstances {
  SceneInstance scene_instances[];
};
layout(set = 1, binding = 2, std430) readonly buffer SceneLights {
  uint scene_lights_count;
  uint scene_lights_pad0;
  uint scene_lights_pad1;
  uint scene_lights_pad2;
  SceneLight scene_lights[];
};
// A shader may bind the two texture arrays elsewhere (with its own sampler) by defining
// SCENE_TEXTURE_SET, SCENE_SRGB_TEXTURE_BINDING and SCENE_LINEAR_TEXTURE_BINDING.
#ifndef SCENE_TEXTURE_SET
#define SCENE_TEXTURE_SET 1
#define SCENE_SRGB_TEXTURE_BINDING 3
#define SCENE_LINEAR_TEXTURE_BINDING 4
#endif
layout(set = SCENE_TEXTURE_SET, binding = SCENE_SRGB_TEXTURE_BINDING) uniform sampler2DArray scene_textures_srgb;
layout(set = SCENE_TEXTURE_SET, binding = SCENE_LINEAR_TEXTURE_BINDING) uniform sampler2DArray scene_textures_linear;

float scene_texture_lod = 0.0;  // with SCENE_TEXTURE_EXPLICIT_LOD

uint scene_light_count() { return scene_lights_count; }

// KHR_lights_punctual's falloff of a point or spot light besides 1/d^2: the range window and the
// spot cone, at distance d from the light along the unit direction from_light (light to point).
// 1 for directional lights.
float scene_light_falloff(SceneLight light, float d, vec3 from_light) {
  if (light.type == SCENE_LIGHT_DIRECTIONAL) return 1.0;
  float falloff = 1.0;
  if (light.range > 0.0) {
    float r = d / light.range;
    falloff *= clamp(1.0 - r * r * r * r, 0.0, 1.0);
  }
  if (light.type == SCENE_LIGHT_SPOT) {
    float len2 = dot(light.direction, light.direction);
    vec3 axis = len2 > 1e-20 ? light.direction * inversesqrt(len2) : vec3(0.0, -1.0, 0.0);
    float s = clamp(dot(axis, from_light) * light.spot_scale + light.spot_offset, 0.0, 1.0);
    falloff *= s * s;
  }
  return falloff;
}

// World-space tangent (xyz) and handedness (w) of a vertex tangent under an instance.
vec4 scene_world_tangent(SceneInstance instance, vec4 tangent) {
  float w = (instance.flags & SCENE_INSTANCE_MIRRORED) != 0u ? -tangent.w : tangent.w;
  return vec4(mat3(instance.world) * tangent.xyz, w);
}

struct MaterialSample {
  vec4 base_color;  // linear RGB, alpha
  float metallic;
  float roughness;  // >= 0.03
  vec3 normal;      // shading normal (unit)
  float occlusion;  // 1 = unoccluded
  vec3 emissive;    // radiance
  bool alpha_mask;  // alpha mode MASK: discard when base_color.a < alpha_cutoff
  bool alpha_blend;
  float alpha_cutoff;
  bool double_sided;
};

// The coordinates slot `slot` samples at: its TEXCOORD set through its transform
// (KHR_texture_transform); scene_texture_uv then clamps clamp-to-edge textures (glTF
// CLAMP_TO_EDGE), since the sampler repeats.
vec2 scene_texture_coords(SceneMaterial m, uint slot, SurfaceAttributes a) {
  vec4 row0 = m.uv_rows[2u * slot];
  vec3 uv = vec3(row0.w > 0.5 ? a.uv1 : a.uv0, 1.0);
  return vec2(dot(row0.xyz, uv), dot(m.uv_rows[2u * slot + 1u].xyz, uv));
}

vec2 scene_texture_uv(SceneMaterial m, uint slot, SurfaceAttributes a) {
  vec2 mapped = scene_texture_coords(m, slot, a);
  return (m.clamp_mask & (1u << slot)) != 0u ? clamp(mapped, 0.0, 1.0) : mapped;
}

vec4 scene_texture_srgb(int layer, vec2 uv) {
#ifdef SCENE_TEXTURE_EXPLICIT_LOD
  return textureLod(scene_textures_srgb, vec3(uv, float(layer)), scene_texture_lod);
#else
  return texture(scene_textures_srgb, vec3(uv, float(layer)));
#endif
}

vec4 scene_texture_linear(int layer, vec2 uv) {
#ifdef SCENE_TEXTURE_EXPLICIT_LOD
  return textureLod(scene_textures_linear, vec3(uv, float(layer)), scene_texture_lod);
#else
  return texture(scene_textures_linear, vec3(uv, float(layer)));
#endif
}

// Base colour and alpha: factor × texture × vertex colour (glTF 2.0, 3.9.2).
vec4 scene_base_color(SceneMaterial m, SurfaceAttributes a) {
  vec4 color = m.base_color * a.color;
  if (m.base_color_tex >= 0) color *= scene_texture_srgb(m.base_color_tex, scene_texture_uv(m, 0u, a));
  return color;
}

// normal and tangent are world-space interpolated vertex values (any length);
// tangent.w is the bitangent sign.
MaterialSample sample_material(uint material, SurfaceAttributes a, vec3 normal, vec4 tangent) {
  SceneMaterial m = scene_materials[material];
  MaterialSample s;
  s.base_color = scene_base_color(m, a);
  s.metallic = m.metallic;
  s.roughness = m.roughness;
  if (m.metallic_roughness_tex >= 0) {
    vec4 mr = scene_texture_linear(m.metallic_roughness_tex, scene_texture_uv(m, 1u, a));
    s.roughness *= mr.g;  // glTF: roughness in green, metallic in blue
    s.metallic *= mr.b;
  }
  s.metallic = clamp(s.metallic, 0.0, 1.0);
  s.roughness = clamp(s.roughness, 0.03, 1.0);

  float n_len2 = dot(normal, normal);
  vec3 n = n_len2 > 1e-20 ? normal * inversesqrt(n_len2) : vec3(0.0, 1.0, 0.0);
  s.normal = n;
  if (m.normal_tex >= 0) {
    // Gram-Schmidt the interpolated tangent; skip the map where the frame is degenerate.
    vec3 t = tangent.xyz - n * dot(n, tangent.xyz);
    float t_len2 = dot(t, t);
    if (t_len2 > 1e-20) {
      t *= inversesqrt(t_len2);
      vec3 b = cross(n, t) * (tangent.w < 0.0 ? -1.0 : 1.0);
      vec3 tn = scene_texture_linear(m.normal_tex, scene_texture_uv(m, 2u, a)).xyz * 2.0 - 1.0;
      tn.xy *= m.normal_scale;
      vec3 mapped = t * tn.x + b * tn.y + n * tn.z;
      float mapped_len2 = dot(mapped, mapped);
      if (mapped_len2 > 1e-20 && !isnan(mapped_len2) && !isinf(mapped_len2)) {
        s.normal = mapped * inversesqrt(mapped_len2);
      }
    }
  }

  s.occlusion = 1.0;
  if (m.occlusion_tex >= 0) {
    float ao = scene_texture_linear(m.occlusion_tex, scene_texture_uv(m, 3u, a)).r;
    s.occlusion = 1.0 + m.occlusion_strength * (ao - 1.0);
  }
  s.emissive = m.emissive;
  if (m.emissive_tex >= 0) {
    s.emissive *= scene_texture_srgb(m.emissive_tex, scene_texture_uv(m, 4u, a)).rgb;
  }
  s.alpha_mask = m.alpha_mode == SCENE_ALPHA_MASK;
  s.alpha_blend = m.alpha_mode == SCENE_ALPHA_BLEND;
  s.alpha_cutoff = m.alpha_cutoff;
  s.double_sided = m.double_sided != 0u;
  if (m.alpha_mode == SCENE_ALPHA_OPAQUE) s.base_color.a = 1.0;
  return s;
}

#endif
