#ifndef VOXGI_VCT_VOLUME_ENCODING_GLSL
#define VOXGI_VCT_VOLUME_ENCODING_GLSL
// Contract: how vct.filter's volumes store a voxel, shared by the filter (which composites in
// premultiplied-radiance / opacity form, the stored form) and the cone tracers of every family
// (which filter it across a cone's travel in hardware and convert it along the travel, below).
// No bindings.
//
// Stored: premultiplied radiance and opacity of one voxel length, (L * a, a), a in [0, 1].
//
// Why premultiplied opacity, and where optical depth comes in: a cone reads the volumes between
// voxel centres, and what it needs differs by direction. Across its travel, texels side by side
// each cover their share of its cross-section, and what covers a share a of it blocks a of the
// light: their opacities average, which the hardware's bilinear filtering of this form does.
// Along its travel, opacity must not be averaged: an opaque one-voxel wall would become a
// two-voxel haze whose transmittance along a ray is e^-2 (about 14%), and every thin wall
// leaked. So the tracer (contracts/cone_trace.glsl, vct_fetch_along) takes the two layers of
// texels that straddle a sample along the travel, each filtered across, turns each into optical
// depth tau = -ln(1 - a) and radiance x tau (which add along a ray), and interpolates those.
// (Storing optical depth and letting the hardware interpolate it in all three directions made
// a texel half covered by an opaque surface 98% opaque across the travel: every surface looked
// a voxel wider on each side; docs/error-budget.md, eleventh round.)

const float VCT_MAX_OPTICAL_DEPTH = 8.0;  // opacity 1 - e^-8 = 0.99966 per voxel length

// From premultiplied radiance and opacity (L * a, a) to the stored form.
vec4 vct_encode_volume(vec4 premultiplied) {
  float a = clamp(premultiplied.a, 0.0, 1.0);
  if (!(a > 0.0)) return vec4(0.0);
  return vec4(max(premultiplied.rgb, vec3(0.0)), a);
}

// Back to premultiplied radiance and opacity: the stored form is that form, kept in range.
vec4 vct_decode_volume(vec4 stored) { return vct_encode_volume(stored); }

// Premultiplied radiance and opacity of one voxel length to the form that adds along a ray:
// a = tau = -ln(1 - opacity) (at most VCT_MAX_OPTICAL_DEPTH), rgb = L * tau /
// VCT_MAX_OPTICAL_DEPTH (the division keeps it within the half-float range for any L).
vec4 vct_optical_depth(vec4 premultiplied) {
  float a = clamp(premultiplied.a, 0.0, 1.0);
  if (!(a > 0.0)) return vec4(0.0);
  float tau = min(-log(max(1.0 - a, 1e-30)), VCT_MAX_OPTICAL_DEPTH);
  return vec4(max(premultiplied.rgb, vec3(0.0)) / a * (tau / VCT_MAX_OPTICAL_DEPTH), tau);
}

#endif
