#ifndef VOXGI_VCT_VOLUME_ENCODING_GLSL
#define VOXGI_VCT_VOLUME_ENCODING_GLSL
// Contract: how vct.filter's volumes store a voxel, shared by the filter (which composites in
// premultiplied-radiance / opacity form and converts when it stores and loads) and the cone
// tracers of every family (which read the stored form through hardware trilinear filtering).
// No bindings.
//
// Stored: a = tau = -ln(1 - opacity), the optical depth of one voxel length, at most
// VCT_MAX_OPTICAL_DEPTH; rgb = L * tau / VCT_MAX_OPTICAL_DEPTH, L the voxel's radiance.
//
// Why optical depth: the tracer samples between voxel centres. Interpolating opacity turns an
// opaque one-voxel wall into a two-voxel haze whose transmittance, integrated along a ray, is
// e^-2 (about 14%, 17% with unit steps): every thin wall leaked, at every level of detail.
// Optical depth and radiance x optical depth add along a ray, so interpolating them keeps each
// voxel's own transmittance and emission: an opaque voxel stays opaque wherever it is sampled.
// The division by the maximum depth keeps rgb within the half-float range for any L.

const float VCT_MAX_OPTICAL_DEPTH = 8.0;  // opacity 1 - e^-8 = 0.99966 per voxel length

// From premultiplied radiance and opacity (L * a, a).
vec4 vct_encode_volume(vec4 premultiplied) {
  float a = clamp(premultiplied.a, 0.0, 1.0);
  if (!(a > 0.0)) return vec4(0.0);
  float tau = min(-log(max(1.0 - a, 1e-30)), VCT_MAX_OPTICAL_DEPTH);
  vec3 radiance = max(premultiplied.rgb, vec3(0.0)) / a;
  return vec4(radiance * (tau / VCT_MAX_OPTICAL_DEPTH), tau);
}

// Back to premultiplied radiance and opacity.
vec4 vct_decode_volume(vec4 stored) {
  float tau = max(stored.a, 0.0);
  if (!(tau > 1e-7)) return vec4(0.0);
  float a = 1.0 - exp(-tau);
  vec3 radiance = max(stored.rgb, vec3(0.0)) * (VCT_MAX_OPTICAL_DEPTH / tau);
  return vec4(radiance * a, a);
}

#endif
