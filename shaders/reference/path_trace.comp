#version 460
#extension GL_GOOGLE_include_directive : require
// Progressive reference path tracer over the scene's BVH: the glTF BRDF (shaders/lib/brdf.glsl)
// sampled by lobe (cosine-weighted Lambert, GGX visible normals), next-event estimation of
// punctual lights (KHR_lights_punctual falloffs) and of emissive triangles, combined with
// BSDF-sampled hits of emitters by multiple importance sampling (power heuristic), and
// unbiased Russian roulette. Each invocation adds `samples` paths of one pixel to running
// sums (persistent accumulation layers) and writes the means and the variances of the means
// of all light and of the indirect layer.
//
// Layers: direct = emission seen directly + light arriving after one reflection;
// indirect = everything else (what GI techniques approximate); linear = direct + indirect.
#define SCENE_TEXTURE_EXPLICIT_LOD
// The scene's texture arrays, bound here with a sampler without anisotropic filtering: with it
// lavapipe samples ~100x slower, and a path tracer samples at LOD 0 anyway.
#define SCENE_TEXTURE_SET 0
#define SCENE_SRGB_TEXTURE_BINDING 10
#define SCENE_LINEAR_TEXTURE_BINDING 11
#include "lib/frame.glsl"
#include "lib/common.glsl"
#include "lib/brdf.glsl"
#include "lib/scene.glsl"
#include "lib/sampling.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// Stochastic transparency of alpha-masked and alpha-blended materials (see bvh_hit_filter).
// Only compiled in for scenes that have such materials (HAS_ALPHA = 1): the lookup sits in the
// innermost loop of the traversal.
#ifndef HAS_ALPHA
#define HAS_ALPHA 0
#endif
uint g_filter_seed = 0u;
// Set while a camera ray of path_tracer.single_sided is traced (see bvh_hit_filter): the faces
// the G-buffer culls do not stop it. A filter rather than a second trace from behind the culled
// face, which would also pass a coincident face that the G-buffer draws.
bool g_cull_backs = false;
vec3 g_ray_dir = vec3(0.0);
bool bvh_hit_filter(uint triangle, float u, float v);
#define BVH_HIT_FILTER
#define BVH_SET 0
#define BVH_FIRST_BINDING 1
#include "lib/bvh_traversal.glsl"

layout(set = 0, binding = 0) uniform FrameBlock { FrameUniforms frame; };
// Layers: 0 sum of radiance (w: sample count), 1 sum of direct, 2 sum of indirect,
// 3 sum of squared radiance, 4 sum of squared indirect.
layout(set = 0, binding = 5, rgba32f) uniform image2DArray accumulation;
layout(set = 0, binding = 6) writeonly uniform image2D out_linear;
layout(set = 0, binding = 7) writeonly uniform image2D out_direct;
layout(set = 0, binding = 8) writeonly uniform image2D out_indirect;
layout(set = 0, binding = 9) writeonly uniform image2D out_variance;
layout(set = 0, binding = 12) writeonly uniform image2D out_indirect_variance;

const uint FLAG_LAMBERT = 1u;
const uint FLAG_PIXEL_JITTER = 2u;
// Layers as a deferred renderer with voxel GI splits them (path_tracer.deferred_layers): direct =
// emission seen from the camera + punctual lights at the first hit (what deferred lighting
// computes); everything else is indirect. Emissive surfaces light the scene with one reflection
// less than punctual lights (max_depth - 1): voxel GI injects emission as voxel radiance, but
// punctual light only after its first reflection.
const uint FLAG_DEFERRED_LAYERS = 4u;
// glTF's single-sided materials (doubleSided false) as the rasterised passes treat them
// (path_tracer.single_sided): camera rays pass through their back faces by winding, which the
// G-buffer culls, and a face that a later ray meets from the side its vertex normals turn away
// from blocks it but reflects and emits nothing, as voxels light and show only the side their
// normals face. The two sides agree unless a mesh's normals contradict its winding.
const uint FLAG_SINGLE_SIDED = 8u;

layout(push_constant) uniform Push {
  vec4 origin;  // xyz: BVH origin in world space
  uvec2 size;
  uint sample_base;  // samples already accumulated; 0 starts over
  uint samples;      // samples to add now
  uint max_depth;    // most reflections a path may make
  uint rr_start;     // reflections before Russian roulette starts
  uint flags;
  uint node_count;
  uint emitter_count;
  // Farther than this from the visible surface (scene units), the first reflection's light is
  // left out, by either sampling strategy (0: no limit): the near part of a reference, to set
  // against cones cut at the same length (cone_trace.max_distance).
  float first_bounce_distance;
  // Only first reflections whose direction's sin^2 to the visible surface's normal lies in
  // [min, max) count (0 and 1: all): a band of the cosine-weighted hemisphere, as one ring of
  // diffuse cones sees it.
  float first_bounce_sin2_min;
  float first_bounce_sin2_max;
} pc;

// Whether a first reflection at distance t counts (first_bounce_distance).
bool within_first_bounce_distance(float t) {
  return pc.first_bounce_distance <= 0.0 || t <= pc.first_bounce_distance;
}

// Whether direction l leaves a surface of normal n within the first reflection's band.
bool in_first_bounce_band(vec3 l, vec3 n) {
  if (pc.first_bounce_sin2_min <= 0.0 && pc.first_bounce_sin2_max >= 1.0) return true;
  float c = dot(l, n);
  float s2 = max(1.0 - c * c, 0.0);
  return s2 >= pc.first_bounce_sin2_min &&
         (s2 < pc.first_bounce_sin2_max || pc.first_bounce_sin2_max >= 1.0);
}

vec2 interpolate2(vec2 a, vec2 b, vec2 c, float u, float v) { return a * (1.0 - u - v) + b * u + c * v; }

SurfaceAttributes surface_attributes(BvhShading s, float u, float v) {
  SurfaceAttributes a;
  a.uv0 = interpolate2(s.uv01.xy, s.uv01.zw, s.uv2, u, v);
  a.uv1 = interpolate2(s.uv1_01.xy, s.uv1_01.zw, s.uv1_2.xy, u, v);
  a.color = s.color[0] * (1.0 - u - v) + s.color[1] * u + s.color[2] * v;
  return a;
}

float material_alpha(uint triangle, float u, float v, out uint alpha_mode, out float cutoff) {
  BvhShading s = bvh_shading[triangle];
  SceneMaterial m = scene_materials[s.material];
  alpha_mode = m.alpha_mode;
  cutoff = m.alpha_cutoff;
  if (m.alpha_mode == SCENE_ALPHA_OPAQUE) return 1.0;
  return scene_base_color(m, surface_attributes(s, u, v)).a;
}

bool single_sided_material(uint triangle) {
  return scene_materials[bvh_shading[triangle].material].double_sided == 0u;
}

// Whether a ray along `ray_d` meets a single-sided material's face from behind its winding
// (the face the G-buffer culls).
bool culled_back(uint triangle, vec3 ray_d) {
  return single_sided_material(triangle) && dot(bvh_triangle_front_normal(triangle), ray_d) > 0.0;
}

// Culled faces pass camera rays (g_cull_backs). Alpha, where the scene has it: MASK: the
// surface exists where alpha >= cutoff. BLEND: it exists with probability alpha, decided per
// (ray, triangle) so that a ray sees one consistent answer.
bool bvh_hit_filter(uint triangle, float u, float v) {
  if (g_cull_backs && culled_back(triangle, g_ray_dir)) return false;
#if HAS_ALPHA
  uint mode;
  float cutoff;
  float alpha = material_alpha(triangle, u, v, mode, cutoff);
  if (mode == SCENE_ALPHA_OPAQUE) return true;
  if (mode == SCENE_ALPHA_MASK) return alpha >= cutoff;
  uint h = pcg_hash(g_filter_seed ^ pcg_hash(triangle));
  return float(h >> 8u) * (1.0 / 16777216.0) < alpha;
#else
  return true;
#endif
}

// Whether a ray along `ray_d` meets a single-sided material at (u, v) of `triangle` from the
// side its vertex normals turn away from (the side its voxels leave dark). The face's own
// plane decides, on the side the interpolated normal leans to.
bool unlit_back(uint triangle, float u, float v, vec3 ray_d) {
  if (!single_sided_material(triangle)) return false;
  BvhShading s = bvh_shading[triangle];
  vec3 n = s.normal[0].xyz * (1.0 - u - v) + s.normal[1].xyz * u + s.normal[2].xyz * v;
  vec3 ng = bvh_triangle_normal(triangle);
  return dot(dot(ng, n) >= 0.0 ? ng : -ng, ray_d) > 0.0;
}

struct Hit {
  vec3 position;     // relative to the BVH origin
  vec3 geometric;    // unit, facing the incoming ray
  vec3 shading;      // unit, on the geometric normal's side
  MaterialSample material;
  float emitter_pdf_area;
};

Hit shade_hit(BvhHit h, vec3 ray_o, vec3 ray_d) {
  Hit hit;
  BvhShading s = bvh_shading[h.triangle];
  float w = 1.0 - h.u - h.v;
  hit.position = ray_o + ray_d * h.t;
  vec3 ng = safe_normalize(bvh_triangle_normal(h.triangle), -ray_d);
  hit.geometric = dot(ng, ray_d) > 0.0 ? -ng : ng;
  vec3 n = s.normal[0].xyz * w + s.normal[1].xyz * h.u + s.normal[2].xyz * h.v;
  vec4 t = s.tangent[0] * w + s.tangent[1] * h.u + s.tangent[2] * h.v;
  hit.material = sample_material(s.material, surface_attributes(s, h.u, h.v), n, t);
  vec3 ns = hit.material.normal;
  hit.shading = dot(ns, hit.geometric) < 0.0 ? -ns : ns;
  hit.emitter_pdf_area = s.emitter_pdf_area;
  return hit;
}

// The surface's reflectance model: the glTF BRDF, or a Lambertian of the base colour.
struct Bsdf {
  SurfaceBrdf brdf;
  bool lambert;
  float specular_probability;  // of sampling the GGX lobe
  float alpha;
};

float max3(vec3 c) { return max(c.x, max(c.y, c.z)); }
float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

Bsdf make_bsdf(MaterialSample m, vec3 n, vec3 v) {
  Bsdf b;
  b.brdf.base_color = m.base_color.rgb;
  b.brdf.metallic = m.metallic;
  b.brdf.roughness = m.roughness;
  b.lambert = (pc.flags & FLAG_LAMBERT) != 0u;
  b.alpha = max(m.roughness * m.roughness, 1e-3);
  if (b.lambert) {
    b.specular_probability = 0.0;
  } else {
    // Pick lobes in proportion to their estimated reflectance at this view angle.
    vec3 f0 = mix(vec3(0.04), m.base_color.rgb, m.metallic);
    vec3 f = fresnel_schlick(f0, max(dot(n, v), 0.0));
    float specular = luminance(f);
    float diffuse = luminance((vec3(1.0) - f) * m.base_color.rgb * (1.0 - m.metallic));
    b.specular_probability = diffuse > 0.0 ? clamp(specular / (specular + diffuse), 0.05, 0.95) : 1.0;
  }
  return b;
}

vec3 bsdf_eval_cos(Bsdf b, vec3 n, vec3 v, vec3 l) {
  if (b.lambert) return b.brdf.base_color * (INV_PI * max(dot(n, l), 0.0));
  return gltf_brdf_cos(b.brdf, n, v, l);
}

float bsdf_pdf(Bsdf b, vec3 n, vec3 v, vec3 l) {
  float n_dot_l = dot(n, l);
  if (n_dot_l <= 0.0) return 0.0;
  float pdf = (1.0 - b.specular_probability) * n_dot_l * INV_PI;
  if (b.specular_probability > 0.0) {
    vec3 h = safe_normalize(v + l, n);
    pdf += b.specular_probability *
           ggx_visible_reflection_pdf(max(dot(n, v), 1e-4), clamp(dot(n, h), 0.0, 1.0), b.alpha);
  }
  return pdf;
}

vec3 bsdf_sample(Bsdf b, vec3 n, vec3 v, inout uint rng) {
  float choice = next_random(rng);
  vec2 u = next_random2(rng);
  if (choice >= b.specular_probability) return sample_cosine_hemisphere(n, u);
  vec3 v_local = to_local(v, n);
  v_local.z = max(v_local.z, 1e-4);
  vec3 h = to_world(sample_ggx_visible_normal(normalize(v_local), b.alpha, u), n);
  return reflect(-v, h);
}

// Start of a ray leaving a surface: far enough along the geometric normal to clear the
// surface's own float error, which grows with the distance from the BVH origin.
vec3 offset_origin(vec3 p, vec3 ng, vec3 dir) {
  vec3 a = abs(p);
  float eps = 1e-5 + 4e-6 * max(a.x, max(a.y, a.z));
  return p + ng * (dot(dir, ng) >= 0.0 ? eps : -eps);
}

bool visible(vec3 from, vec3 dir, float distance_to, inout uint rng) {
  g_filter_seed = pcg_hash(rng);
  rng = g_filter_seed;
  return !bvh_trace(from, dir, 0.0, distance_to, pc.node_count, true).hit;
}

// Emission of an emitter seen from a direction: glTF emission on both faces, scaled by the
// probability that a stochastically transparent surface is there.
vec3 emitted(MaterialSample m) {
  return m.alpha_blend ? m.emissive * m.base_color.a : m.emissive;
}

// Direct light from the punctual lights and one sampled emissive triangle (MIS-weighted).
// Light arriving at `hit` straight from the punctual lights (returned) and, in `from_emitters`,
// from one sampled emissive triangle (MIS-weighted against BSDF sampling).
// At the visible surface (`first_bounce`), emitters beyond first_bounce_distance or outside the
// first reflection's band are left out (after their random numbers are drawn, so that a cut
// changes no other term of the path).
vec3 next_event(Hit hit, Bsdf b, vec3 v, bool first_bounce, inout uint rng,
                out vec3 from_emitters) {
  vec3 n = hit.shading;
  vec3 result = vec3(0.0);
  from_emitters = vec3(0.0);
  uint light_count = scene_light_count();
  for (uint i = 0u; i < light_count; ++i) {
    SceneLight light = scene_lights[i];
    vec3 l;
    float attenuation = 1.0;
    float distance_to_light = 1e30;
    if (light.type == SCENE_LIGHT_DIRECTIONAL) {
      l = safe_normalize(-light.direction, vec3(0.0, 1.0, 0.0));
    } else {
      vec3 to_light = (light.position - pc.origin.xyz) - hit.position;
      // As the rasterised lighting: a light on (or in) a surface must not give 1/0.
      float d2 = max(dot(to_light, to_light), 1e-8);
      distance_to_light = sqrt(d2);
      l = to_light / distance_to_light;
      attenuation = scene_light_falloff(light, distance_to_light, -l) / d2;
    }
    if (attenuation <= 0.0 || dot(n, l) <= 0.0 || dot(hit.geometric, l) <= 0.0) continue;
    vec3 f = bsdf_eval_cos(b, n, v, l) * light.radiance * attenuation;
    if (max3(f) <= 0.0) continue;
    vec3 from = offset_origin(hit.position, hit.geometric, l);
    if (visible(from, l, distance_to_light * (1.0 - 1e-5), rng)) result += f;
  }

  if (pc.emitter_count > 0u) {
    // Pick an emitter by power (binary search of the CDF), then a uniform point on it.
    float pick = next_random(rng);
    uint lo = 0u, hi = pc.emitter_count - 1u;
    while (lo < hi) {
      uint mid = (lo + hi) / 2u;
      if (bvh_emitters[mid].cdf < pick) lo = mid + 1u; else hi = mid;
    }
    uint triangle = bvh_emitters[lo].triangle;
    vec2 u = next_random2(rng);
    float su = sqrt(u.x);
    float bu = u.y * su;      // weight of v1
    float bv = 1.0 - su;      // weight of v2
    BvhTriangle tri = bvh_triangles[triangle];
    vec3 p = tri.v0.xyz * (1.0 - bu - bv) + tri.v1.xyz * bu + tri.v2.xyz * bv;
    vec3 to_p = p - hit.position;
    float d2 = dot(to_p, to_p);
    vec3 light_normal = safe_normalize(bvh_triangle_normal(triangle), vec3(0.0));
    if (d2 > 1e-20) {
      float d = sqrt(d2);
      vec3 l = to_p / d;
      float cos_light = abs(dot(light_normal, l));
      float pdf_light = bvh_shading[triangle].emitter_pdf_area * d2 / max(cos_light, 1e-8);
      if (cos_light > 1e-6 && dot(n, l) > 0.0 && dot(hit.geometric, l) > 0.0 && pdf_light > 0.0) {
        BvhShading s = bvh_shading[triangle];
        float w = 1.0 - bu - bv;
        MaterialSample m = sample_material(s.material, surface_attributes(s, bu, bv), s.normal[0].xyz * w + s.normal[1].xyz * bu + s.normal[2].xyz * bv,
                                           s.tangent[0] * w + s.tangent[1] * bu + s.tangent[2] * bv);
        vec3 f = bsdf_eval_cos(b, n, v, l) * emitted(m);
        // Seen from behind, a single-sided emitter sends nothing (l runs towards it).
        if ((pc.flags & FLAG_SINGLE_SIDED) != 0u && unlit_back(triangle, bu, bv, l)) {
          f = vec3(0.0);
        }
        if (max3(f) > 0.0) {
          vec3 from = offset_origin(hit.position, hit.geometric, l);
          vec3 a = abs(p);
          float end_eps = 1e-5 + 4e-6 * max(a.x, max(a.y, a.z));
          if (visible(from, l, max(distance(from, p) - 2.0 * end_eps, 0.0), rng)) {
            from_emitters = f * (mis_power(pdf_light, bsdf_pdf(b, n, v, l)) / pdf_light);
            // Cut after the visibility ray: a path draws the same numbers whatever the cut.
            if (first_bounce &&
                !(within_first_bounce_distance(d) && in_first_bounce_band(l, n))) {
              from_emitters = vec3(0.0);
            }
          }
        }
      }
    }
  }
  return result;
}

// One path through pixel `pixel`; adds its direct and indirect parts.
void trace_path(uvec2 pixel, inout uint rng, out vec3 direct, out vec3 indirect) {
  direct = vec3(0.0);
  indirect = vec3(0.0);
  // Camera ray through a uniformly jittered point of the pixel (a 1-pixel box filter), or
  // through its centre (to compare pixel by pixel with rasterised passes).
  vec2 jitter = (pc.flags & FLAG_PIXEL_JITTER) != 0u ? next_random2(rng) : vec2(0.5);
  vec2 uv = (vec2(pixel) + jitter) / vec2(pc.size);
  vec4 view = frame.inv_proj * vec4(uv * 2.0 - 1.0, 1.0, 1.0);
  vec3 dir = normalize(mat3(frame.inv_view) * safe_normalize(view.xyz / view.w, vec3(0.0, 0.0, -1.0)));
  vec3 origin = frame.camera_position.xyz - pc.origin.xyz;
  vec3 throughput = vec3(1.0);
  float previous_pdf = 0.0;  // BSDF density of the direction that led here
  bool deferred = (pc.flags & FLAG_DEFERRED_LAYERS) != 0u;
  bool single_sided_mode = (pc.flags & FLAG_SINGLE_SIDED) != 0u;

  for (uint depth = 0u;; ++depth) {
    g_filter_seed = pcg_hash(rng);
    rng = g_filter_seed;
    g_cull_backs = single_sided_mode && depth == 0u;
    g_ray_dir = dir;
    BvhHit h = bvh_trace(origin, dir, 0.0, 3.0e38, pc.node_count, false);
    g_cull_backs = false;
    // A later ray ends on an unlit back.
    if (single_sided_mode && depth > 0u && h.hit && unlit_back(h.triangle, h.u, h.v, dir)) break;
    if (!h.hit) break;  // no environment light
    if (depth == 1u && !within_first_bounce_distance(h.t)) break;
    Hit hit = shade_hit(h, origin, dir);

    vec3 le = emitted(hit.material);
    if (max3(le) > 0.0) {
      float weight = 1.0;
      if (depth > 0u && pc.emitter_count > 0u && hit.emitter_pdf_area > 0.0) {
        float cos_light = abs(dot(hit.geometric, dir));
        float pdf_light = hit.emitter_pdf_area * h.t * h.t / max(cos_light, 1e-8);
        weight = mis_power(previous_pdf, pdf_light);
      }
      vec3 contribution = throughput * le * weight;
      if (!deferred) {
        if (depth <= 1u) direct += contribution; else indirect += contribution;
      } else if (depth == 0u) {
        direct += contribution;
      } else if (depth < pc.max_depth) {
        indirect += contribution;
      }
    }
    if (depth >= pc.max_depth) break;

    vec3 v = -dir;
    Bsdf b = make_bsdf(hit.material, hit.shading, v);
    vec3 emitter_light;
    vec3 light = throughput * next_event(hit, b, v, depth == 0u, rng, emitter_light);
    emitter_light *= throughput;
    if (!deferred) {
      light += emitter_light;
      if (depth == 0u) direct += light; else indirect += light;
    } else {
      if (depth == 0u) direct += light; else indirect += light;
      if (depth + 1u < pc.max_depth) indirect += emitter_light;
    }

    vec3 l = bsdf_sample(b, hit.shading, v, rng);
    float pdf = bsdf_pdf(b, hit.shading, v, l);
    if (!(pdf > 0.0) || dot(l, hit.geometric) <= 0.0) break;
    if (depth == 0u && !in_first_bounce_band(l, hit.shading)) break;
    vec3 weight = bsdf_eval_cos(b, hit.shading, v, l) / pdf;
    throughput *= weight;
    if (depth + 1u > pc.rr_start) {
      float survive = min(max3(throughput), 0.95);
      if (!(next_random(rng) < survive)) break;
      throughput /= survive;
    }
    if (!(max3(throughput) > 0.0) || isinf(max3(throughput))) break;
    previous_pdf = pdf;
    origin = offset_origin(hit.position, hit.geometric, l);
    dir = l;
  }
}

// Replaces NaN and Inf (which only a bug could produce) so one sample cannot poison the sums.
vec3 finite_or_zero(vec3 c) {
  return mix(c, vec3(0.0), bvec3(isnan(c.x) || isinf(c.x), isnan(c.y) || isinf(c.y), isnan(c.z) || isinf(c.z)));
}

// Unbiased sample variance divided by n: the variance of the mean of n samples whose squares
// sum to `sum_sq`. Unknown (the half maximum) until there are two samples.
vec3 variance_of_mean(vec3 sum_sq, vec3 mean, float n) {
  return n > 1.5 ? max(sum_sq / n - mean * mean, vec3(0.0)) * (n / (n - 1.0)) / n : vec3(HALF_MAX);
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, pc.size))) return;
  ivec2 p = ivec2(pixel);
  vec4 sum = vec4(0.0), sum_direct = vec4(0.0), sum_indirect = vec4(0.0), sum_sq = vec4(0.0);
  vec4 sum_indirect_sq = vec4(0.0);
  if (pc.sample_base > 0u) {
    sum = imageLoad(accumulation, ivec3(p, 0));
    sum_direct = imageLoad(accumulation, ivec3(p, 1));
    sum_indirect = imageLoad(accumulation, ivec3(p, 2));
    sum_sq = imageLoad(accumulation, ivec3(p, 3));
    sum_indirect_sq = imageLoad(accumulation, ivec3(p, 4));
  }
  for (uint s = 0u; s < pc.samples; ++s) {
    uint rng = sample_seed(pixel, pc.sample_base + s);
    vec3 direct, indirect;
    trace_path(pixel, rng, direct, indirect);
    direct = finite_or_zero(direct);
    indirect = finite_or_zero(indirect);
    vec3 radiance = direct + indirect;
    sum += vec4(radiance, 1.0);
    sum_direct.rgb += direct;
    sum_indirect.rgb += indirect;
    sum_sq.rgb += radiance * radiance;
    sum_indirect_sq.rgb += indirect * indirect;
  }
  imageStore(accumulation, ivec3(p, 0), sum);
  imageStore(accumulation, ivec3(p, 1), sum_direct);
  imageStore(accumulation, ivec3(p, 2), sum_indirect);
  imageStore(accumulation, ivec3(p, 3), sum_sq);
  imageStore(accumulation, ivec3(p, 4), sum_indirect_sq);

  float n = max(sum.w, 1.0);
  vec3 mean = sum.rgb / n;
  vec3 indirect_mean = sum_indirect.rgb / n;
  imageStore(out_linear, p, vec4(sanitize_radiance(mean), 1.0));
  imageStore(out_direct, p, vec4(sanitize_radiance(sum_direct.rgb / n), 1.0));
  imageStore(out_indirect, p, vec4(sanitize_radiance(indirect_mean), 1.0));
  vec3 variance = variance_of_mean(sum_sq.rgb, mean, n);
  vec3 indirect_variance = variance_of_mean(sum_indirect_sq.rgb, indirect_mean, n);
  imageStore(out_variance, p, vec4(sanitize_radiance(variance), sum.w));
  imageStore(out_indirect_variance, p, vec4(sanitize_radiance(indirect_variance), sum.w));
}
