#ifndef VOXGI_VCT_GBUFFER_SAMPLE_GLSL
#define VOXGI_VCT_GBUFFER_SAMPLE_GLSL
// G-buffer access shared by the vct trace and upsample shaders (bindings 2..6 of set 0); the
// encoding is the contract's (contracts/gbuffer.glsl).

#include "contracts/gbuffer.glsl"
#include "lib/brdf.glsl"
#include "lib/common.glsl"

#ifndef SPECULAR_LAYER
#define SPECULAR_LAYER 0
#endif

layout(set = 0, binding = 2) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 3) uniform sampler2D g_base_color;
layout(set = 0, binding = 4) uniform sampler2D g_normal;
layout(set = 0, binding = 5) uniform sampler2D g_material;
layout(set = 0, binding = 6) uniform sampler2D g_depth;

struct GbufferSample {
  bool valid;  // false where no geometry was drawn
  vec3 position;
  vec3 normal;
  vec3 base_color;
  float metallic;
  float roughness;
  float view_depth;  // distance along the view axis (m)
};

ivec2 gbuffer_size() { return textureSize(g_depth, 0); }

float gbuffer_view_depth(ivec2 pixel, float depth) {
  vec2 uv = (vec2(pixel) + 0.5) / vec2(gbuffer_size());
  vec4 view = frame.inv_proj * vec4(uv * 2.0 - 1.0, depth, 1.0);
  return abs(view.z / view.w);
}

GbufferSample gbuffer_sample(ivec2 pixel) {
  GbufferSample g;
  pixel = clamp(pixel, ivec2(0), gbuffer_size() - 1);
  float depth = texelFetch(g_depth, pixel, 0).r;
  g.valid = gbuffer_has_surface(depth);
  vec2 uv = (vec2(pixel) + 0.5) / vec2(gbuffer_size());
  g.position = reconstruct_world_position(frame.inv_proj, frame.inv_view, uv, depth);
  vec4 normal_roughness = texelFetch(g_normal, pixel, 0);
  g.normal = gbuffer_normal(normal_roughness);
  g.base_color = gbuffer_base_color(texelFetch(g_base_color, pixel, 0));
  g.metallic = gbuffer_metallic(texelFetch(g_material, pixel, 0));
  g.roughness = gbuffer_roughness(normal_roughness);
  g.view_depth = g.valid ? gbuffer_view_depth(pixel, depth) : 0.0;
  return g;
}

// The share of the light arriving around the mirror direction that the surface reflects
// towards the camera: the specular lobe's directional albedo (lib/brdf.glsl), what
// vct.cone_trace_specular multiplies its cone's radiance by.
vec3 gbuffer_specular_weight(GbufferSample g) {
  vec3 v = safe_normalize(frame.camera_position.xyz - g.position, g.normal);
  vec3 f0 = mix(vec3(0.04), g.base_color, g.metallic);
  return specular_directional_albedo(f0, g.roughness, clamp(dot(g.normal, v), 0.0, 1.0));
}

// Diffuse reflectance c_diff = base colour x (1 - metallic): what the gathered E / pi is
// multiplied by, per full-resolution pixel, after any averaging or upsampling. With the
// specular layer (SPECULAR_LAYER: the graph adds vct.cone_trace_specular's light on every
// pixel) the diffuse reflects only what the specular weight S leaves, (1 - S) c_diff, as the
// direct light's BRDF leaves 1 - F; otherwise diffuse and specular together reflect 1 + S.
vec3 gbuffer_diffuse_reflectance(GbufferSample g) {
  vec3 c_diff = g.base_color * (1.0 - g.metallic);
#if SPECULAR_LAYER
  c_diff *= vec3(1.0) - gbuffer_specular_weight(g);
#endif
  return c_diff;
}

// The full-resolution pixel a half-resolution pixel is traced from: the nearest (smallest
// depth) of its 2x2 block, so silhouettes keep the foreground surface. Deterministic, so the
// upsampler can find it again.
ivec2 gbuffer_block_representative(ivec2 half_pixel) {
  ivec2 size = gbuffer_size();
  ivec2 best = min(half_pixel * 2, size - 1);
  float best_depth = 2.0;
  for (int i = 0; i < 4; ++i) {
    ivec2 q = min(half_pixel * 2 + ivec2(i & 1, i >> 1), size - 1);
    float d = texelFetch(g_depth, q, 0).r;
    if (!isnan(d) && d < best_depth) {
      best_depth = d;
      best = q;
    }
  }
  return best;
}

#endif
