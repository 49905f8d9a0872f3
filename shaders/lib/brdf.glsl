#ifndef VOXGI_BRDF_GLSL
#define VOXGI_BRDF_GLSL
// The glTF 2.0 metallic-roughness BRDF (specification, Appendix B): Lambert diffuse and
// GGX/Smith specular, mixed by Schlick's Fresnel. Every technique and the reference path
// tracer use this one model so that differences between them measure the technique.

const float PI = 3.14159265358979323846;
const float INV_PI = 0.31830988618379067154;

struct SurfaceBrdf {
  vec3 base_color;
  float metallic;
  float roughness;  // perceptual; alpha = roughness^2
};

vec3 fresnel_schlick(vec3 f0, float v_dot_h) {
  float m = clamp(1.0 - v_dot_h, 0.0, 1.0);
  float m2 = m * m;
  return f0 + (vec3(1.0) - f0) * (m2 * m2 * m);
}

// Directional albedo of the specular lobe for a view at n.v: the specular BRDF's cosine-weighted
// integral over the hemisphere, f0 A + B. A and B are the analytic fit of the split-sum table
// in Karis, "Physically Based Shading on Mobile" (2014), in perceptual roughness. Unlike
// Schlick's F(n.v) it falls with roughness at grazing views (0.02 rather than 0.35 for a
// roughness-1 dielectric at n.v = 0.2), and it is below 1 for a white metal (0.89 at roughness
// 0.2), as single-scattering GGX is.
vec3 specular_directional_albedo(vec3 f0, float roughness, float n_dot_v) {
  vec4 r = roughness * vec4(-1.0, -0.0275, -0.572, 0.022) + vec4(1.0, 0.0425, 1.04, -0.04);
  float a004 = min(r.x * r.x, exp2(-9.28 * n_dot_v)) * r.x + r.y;
  vec2 scale_bias = vec2(-1.04, 1.04) * a004 + r.zw;
  return clamp(f0 * scale_bias.x + scale_bias.y, vec3(0.0), vec3(1.0));
}

float ggx_distribution(float n_dot_h, float alpha) {
  float a2 = alpha * alpha;
  float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  return a2 / max(PI * d * d, 1e-12);
}

// Separable Smith visibility, V = G / (4 |N.L| |N.V|), as in the specification.
float smith_visibility(float n_dot_l, float n_dot_v, float alpha) {
  float a2 = alpha * alpha;
  float gl = n_dot_l + sqrt(a2 + (1.0 - a2) * n_dot_l * n_dot_l);
  float gv = n_dot_v + sqrt(a2 + (1.0 - a2) * n_dot_v * n_dot_v);
  return 1.0 / max(gl * gv, 1e-12);
}

// f(l, v) * (n . l): multiply by the incident irradiance-normalised radiance (E) to get the
// reflected radiance. Returns 0 below the horizon, never NaN for grazing or degenerate input.
vec3 gltf_brdf_cos(SurfaceBrdf s, vec3 n, vec3 v, vec3 l) {
  float n_dot_l = dot(n, l);
  float n_dot_v = dot(n, v);
  if (n_dot_l <= 0.0) return vec3(0.0);
  n_dot_v = max(n_dot_v, 1e-4);  // shading normals can face slightly away from the viewer
  vec3 h = l + v;
  float h_len = length(h);
  h = h_len > 1e-6 ? h / h_len : n;
  float n_dot_h = clamp(dot(n, h), 0.0, 1.0);
  float v_dot_h = clamp(dot(v, h), 0.0, 1.0);
  float alpha = max(s.roughness * s.roughness, 1e-3);

  vec3 f0 = mix(vec3(0.04), s.base_color, s.metallic);
  vec3 c_diff = mix(s.base_color, vec3(0.0), s.metallic);
  vec3 f = fresnel_schlick(f0, v_dot_h);
  vec3 diffuse = (vec3(1.0) - f) * INV_PI * c_diff;
  vec3 specular = f * ggx_distribution(n_dot_h, alpha) * smith_visibility(n_dot_l, n_dot_v, alpha);
  return (diffuse + specular) * n_dot_l;
}

#endif
