#version 460
#extension GL_GOOGLE_include_directive : require
// lpv.rsm: reflective shadow map texels (docs/lpv.md, "Reflective shadow maps"). Each texel is
// the first surface the light sees through it and the flux that surface reflects, a virtual
// point light for injection:
//   point / spot:  Phi = c_diff * I * falloff * omega_texel   (omega: the texel's solid angle)
//   directional:   Phi = c_diff * E * area_texel              (area: the texel's cross-section)
// The surface's irradiance I cos / d^2 over its patch of area omega d^2 / cos gives I omega:
// no cosine and no distance appear. c_diff = base colour x (1 - metallic), the Lambert part the
// family propagates. The normal is turned towards the light (double-sided and edge-on
// surfaces still reflect on the lit side).
#include "lib/common.glsl"
#include "lib/scene.glsl"
#include "lpv/rsm_push.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_tangent;
layout(location = 3) in vec2 in_uv;
layout(location = 4) flat in uint in_material;
layout(location = 5) in vec2 in_uv1;
layout(location = 6) in vec4 in_color;

layout(location = 0) out vec4 out_flux;      // rgb reflected flux (W), a 1
layout(location = 1) out vec4 out_normal;    // xyz unit normal facing the light, w 1
layout(location = 2) out vec4 out_position;  // xyz world position, w 1

// Solid angle of the texel under the fragment: the integral of (1 + x^2 + y^2)^(-3/2) over it
// on the image plane at distance 1, by 2 x 2 Gauss-Legendre points (exact to ~1e-6 for texels
// of a few degrees; the centre rule alone is off by ~0.1% at 16^2).
float texel_solid_angle(vec2 frag) {
  float step = 2.0 * pc.info.y / pc.info.z;
  vec2 centre = (frag / pc.info.z) * 2.0 * pc.info.y - pc.info.y;
  float h = step * 0.28867513459481287;  // step / (2 sqrt(3))
  float sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    vec2 q = centre + vec2((i & 1) == 0 ? -h : h, (i & 2) == 0 ? -h : h);
    float r2 = 1.0 + dot(q, q);
    sum += inversesqrt(r2 * r2 * r2);
  }
  return 0.25 * step * step * sum;
}

void main() {
  SceneLight light = scene_lights[uint(pc.origin.w)];
  vec3 to_light;
  float d = 0.0;
  if (light.type == SCENE_LIGHT_DIRECTIONAL) {
    to_light = -safe_normalize(light.direction, vec3(0.0, -1.0, 0.0));
  } else {
    vec3 v = light.position - in_world;
    d = length(v);
    to_light = d > 0.0 ? v / d : vec3(0.0, 1.0, 0.0);
  }
  vec3 geometric = safe_normalize(in_normal, to_light);
  bool flip = dot(geometric, to_light) < 0.0;
  vec4 tangent = vec4(flip ? -in_tangent.xyz : in_tangent.xyz, in_tangent.w);
  MaterialSample m = sample_material(in_material, SurfaceAttributes(in_uv, in_uv1, in_color),
                                     flip ? -geometric : geometric, tangent);
  if (m.alpha_mask && m.base_color.a < m.alpha_cutoff) discard;
  vec3 n = dot(m.normal, to_light) < 0.0 ? -m.normal : m.normal;

  vec3 c_diff = clamp(m.base_color.rgb, vec3(0.0), vec3(1.0)) * (1.0 - clamp(m.metallic, 0.0, 1.0));
  float texel;
  if (pc.info.x > 0.5) {
    texel = texel_solid_angle(gl_FragCoord.xy) * scene_light_falloff(light, d, -to_light);
  } else {
    float side = 2.0 * pc.info.y / pc.info.z;
    texel = side * side;
  }
  out_flux = vec4(sanitize_radiance(c_diff * light.radiance * texel), 1.0);
  out_normal = vec4(n, 1.0);
  out_position = vec4(in_world, 1.0);
}
