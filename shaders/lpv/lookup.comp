#version 460
#extension GL_GOOGLE_include_directive : require
// lpv.lookup: indirect diffuse light per pixel from the accumulated LPV (seed 002 sec. 3.2.4;
// docs/lpv.md). A cell's SH is the radiant intensity I(w) of the light that crossed it; over
// the cell's cross-section s^2 that is radiance L = I / s^2. The irradiance on a surface of
// normal n is the integral of L(w) max(0, -n.w), the dot product with the clamped cosine
// around -n; the pixel's outgoing radiance is c_diff / pi x E. The SH is interpolated
// trilinearly between cell centres at the surface moved `normal_offset` cells along its
// normal (so a wall reads the cells in front of it, not its own: back-bleeding, seed sec.
// 6.1), on the finest level whose window holds it, plus the light the coarser levels carry from
// outside that window, blended into the next level over the last two cells before the window's
// edge.
#include "lib/common.glsl"
#include "lib/frame.glsl"
#include "lpv/sh.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"
#include "contracts/gbuffer.glsl"
#include "lpv/cells.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 1, std430) readonly buffer Accumulated { vec4 accumulated[]; };
layout(set = 0, binding = 2) uniform FrameBlock { FrameUniforms frame; };
layout(set = 0, binding = 3) uniform sampler2D g_base_color;
layout(set = 0, binding = 4) uniform sampler2D g_normal;
layout(set = 0, binding = 5) uniform sampler2D g_material;
layout(set = 0, binding = 6) uniform sampler2D g_depth;
layout(set = 0, binding = 7, rgba16f) writeonly uniform image2D out_diffuse;

layout(push_constant) uniform Push {
  float normal_offset;  // cells
  uint surface_flux;    // 1: irradiance from the flux the geometry stopped
  float pad1;
  float pad2;
} pc;

// Irradiance at the anchor-relative point q from volume `cascade` of level `level`
// (lpv/cells.glsl), trilinear between cell centres (clamped to the window).
vec3 level_irradiance(vec3 q, vec3 n, int level, int cascade) {
  int r = voxel_resolution();
  float s = voxel_size(level);
  vec3 coord = voxel_window_coord(q, level) - 0.5;
  ivec3 base = ivec3(floor(coord));
  vec3 t = coord - vec3(base);
  vec4 cosine = sh_clamped_cosine(-n);
  vec3 e = vec3(0.0);
  for (int i = 0; i < 8; ++i) {
    ivec3 o = ivec3(i & 1, (i >> 1) & 1, i >> 2);
    ivec3 c = clamp(base + o, ivec3(0), ivec3(r - 1));
    vec3 w3 = mix(vec3(1.0) - t, t, vec3(o));
    float w = w3.x * w3.y * w3.z;
    if (w <= 0.0) continue;
    int cell = lpv_cell(c, cascade);
    int at = cell * LPV_RECORD_VEC4S;
    e += w * vec3(dot(accumulated[at], cosine), dot(accumulated[at + 1], cosine),
                  dot(accumulated[at + 2], cosine));
  }
  return max(e, vec3(0.0)) / (s * s);
}

// Irradiance from the flux the geometry stopped in volume `cascade` of level `level`: the cells
// around p whose surface faces the same way as n, trilinearly weighted, each giving stopped
// flux / s^2. Returns false where no such cell is near.
bool surface_irradiance(vec3 p, vec3 n, int level, int cascade, out vec3 e) {
  int r = voxel_resolution();
  float s = voxel_size(level);
  vec3 coord = voxel_window_coord(p, level) - 0.5;
  ivec3 base = ivec3(floor(coord));
  vec3 t = coord - vec3(base);
  vec3 sum = vec3(0.0);
  float weights = 0.0;
  for (int i = 0; i < 8; ++i) {
    ivec3 o = ivec3(i & 1, (i >> 1) & 1, i >> 2);
    ivec3 c = base + o;
    if (!lpv_inside(c)) continue;
    vec3 w3 = mix(vec3(1.0) - t, t, vec3(o));
    float w = w3.x * w3.y * w3.z;
    int at = lpv_cell(c, cascade) * LPV_RECORD_VEC4S;
    vec4 g = accumulated[at + 4];
    float len = length(g.xyz);
    bool same_surface = g.w > 0.0 && (len < 0.25 || dot(g.xyz, n) > 0.25 * len);
    if (!same_surface || !(w > 0.0)) continue;
    // The surface stops opacity x the light crossing the cell: its area is opacity x s^2.
    sum += w * accumulated[at + 3].rgb / g.w;
    weights += w;
  }
  e = weights > 1e-4 ? max(sum / weights, vec3(0.0)) / (s * s) : vec3(0.0);
  return weights > 1e-4;
}

vec3 volume_irradiance(vec3 p, vec3 n, int level, int cascade) {
  vec3 e;
  if (pc.surface_flux != 0u && surface_irradiance(p, n, level, cascade, e)) return e;
  return level_irradiance(p + n * (pc.normal_offset * voxel_size(level)), n, level, cascade);
}

// The light of the sources inside level's window, plus that of the sources outside it, which
// each coarser level's "outer" volume holds (lpv/cells.glsl).
vec3 irradiance(vec3 p, vec3 n, int level) {
  vec3 e = volume_irradiance(p, n, level, level);
  for (int coarser = level + 1; coarser < voxel_level_count(); ++coarser) {
    if (voxel_level_valid(coarser)) {
      e += volume_irradiance(p, n, coarser, lpv_outer_cascade(coarser));
    }
  }
  return e;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(out_diffuse);
  if (any(greaterThanEqual(pixel, size))) return;
  float depth = texelFetch(g_depth, pixel, 0).r;
  vec3 result = vec3(0.0);
  if (gbuffer_has_surface(depth)) {
    vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
    vec3 p = voxel_relative(reconstruct_world_position(frame.inv_proj, frame.inv_view, uv, depth));
    vec3 n = gbuffer_normal(texelFetch(g_normal, pixel, 0));
    vec3 base_color = gbuffer_base_color(texelFetch(g_base_color, pixel, 0));
    float metallic = gbuffer_metallic(texelFetch(g_material, pixel, 0));
    vec3 c_diff = base_color * (1.0 - metallic);
    int level = voxel_finest_level(p, 0.0);
    // A surface on the outer boundary of the coarsest window (a volume fitted to the scene
    // ends at its bounds) still reads the cells next to it.
    if (level < 0 && voxel_finest_level(p, -1.0) >= 0) level = voxel_level_count() - 1;
    if (level >= 0) {
      vec3 e = irradiance(p, n, level);
      if (level + 1 < voxel_level_count()) {
        vec3 coord = voxel_window_coord(p, level);
        float edge = min(min(coord.x, min(coord.y, coord.z)),
                         float(voxel_resolution()) - max(coord.x, max(coord.y, coord.z)));
        float w = clamp(edge * 0.5, 0.0, 1.0);
        if (w < 1.0) {
          e = mix(irradiance(p, n, level + 1), e, w);
        }
      }
      result = c_diff / SH_PI * e;
    }
  }
  imageStore(out_diffuse, pixel, vec4(sanitize_radiance(result), 1.0));
}
