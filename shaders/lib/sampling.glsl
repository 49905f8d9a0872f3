#ifndef VOXGI_SAMPLING_GLSL
#define VOXGI_SAMPLING_GLSL
// Random numbers and direction sampling for Monte Carlo estimators: a PCG hash for
// deterministic per-(pixel, sample) sequences, orthonormal bases, cosine-weighted hemisphere
// sampling and sampling of the GGX distribution of visible normals (Heitz 2018).

// PCG-style integer hash (O'Neill's permuted congruential output).
uint pcg_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// A seed from a pixel and a sample index: the same pair always gives the same sequence.
uint sample_seed(uvec2 pixel, uint sample_index) {
  return pcg_hash(pixel.x ^ pcg_hash(pixel.y ^ pcg_hash(sample_index + 0x9e3779b9u)));
}

// Uniform in [0, 1) with 24 bits; advances the state.
float next_random(inout uint state) {
  state = pcg_hash(state);
  return float(state >> 8u) * (1.0 / 16777216.0);
}

vec2 next_random2(inout uint state) {
  float a = next_random(state);
  return vec2(a, next_random(state));
}

// Tangent and bitangent completing the unit vector n to a right-handed basis (Duff et al.
// 2017); continuous everywhere except across n.z = 0's sign, and never degenerate.
void orthonormal_basis(vec3 n, out vec3 t, out vec3 b) {
  float s = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

vec3 to_world(vec3 local, vec3 n) {
  vec3 t, b;
  orthonormal_basis(n, t, b);
  return t * local.x + b * local.y + n * local.z;
}

vec3 to_local(vec3 w, vec3 n) {
  vec3 t, b;
  orthonormal_basis(n, t, b);
  return vec3(dot(w, t), dot(w, b), dot(w, n));
}

// Cosine-weighted direction around n; pdf = cos(theta) / pi.
vec3 sample_cosine_hemisphere(vec3 n, vec2 u) {
  float r = sqrt(u.x);
  float phi = 6.28318530717958647692 * u.y;
  vec3 local = vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - u.x)));
  return to_world(local, n);
}

// A microfacet normal of the GGX distribution with roughness alpha, visible from the local
// view direction v_local (z = normal, v_local.z > 0).
vec3 sample_ggx_visible_normal(vec3 v_local, float alpha, vec2 u) {
  vec3 vh = normalize(vec3(alpha * v_local.x, alpha * v_local.y, v_local.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = len2 > 0.0 ? vec3(-vh.y, vh.x, 0.0) * inversesqrt(len2) : vec3(1.0, 0.0, 0.0);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = 6.28318530717958647692 * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5 * (1.0 + vh.z);
  p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(1e-6, nh.z)));
}

// Density of the reflected direction when the half vector follows the visible-normal
// distribution: D(h) G1(v) / (4 n.v), with Smith's G1 written out so n.v cancels.
float ggx_visible_reflection_pdf(float n_dot_v, float n_dot_h, float alpha) {
  float a2 = alpha * alpha;
  float d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
  float distribution = a2 / max(3.14159265358979323846 * d * d, 1e-12);
  return distribution / max(2.0 * (n_dot_v + sqrt(a2 + (1.0 - a2) * n_dot_v * n_dot_v)), 1e-12);
}

// Power heuristic (beta = 2) weight of strategy a against b.
float mis_power(float pdf_a, float pdf_b) {
  float a2 = pdf_a * pdf_a;
  float sum = a2 + pdf_b * pdf_b;
  return sum > 0.0 ? a2 / sum : 0.0;
}

#endif
