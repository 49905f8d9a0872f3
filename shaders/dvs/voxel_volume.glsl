#ifndef VOXGI_DVS_VOXEL_VOLUME_GLSL
#define VOXGI_DVS_VOXEL_VOLUME_GLSL
// Per-voxel helpers of the dvs shaders on top of contracts/voxel_clipmap.glsl (include that first):
// the inverse of the toroidal addressing (texel -> voxel position), trilinear opacity with
// the wrap applied per corner, and the normal-weighted attenuation of Villegas §2.1.

#include "lib/common.glsl"

// The clipmap level of a texel of the stacked image and the voxel's centre relative to the
// anchor. R is a power of two, so "& (R - 1)" is the toroidal modulo for negative indices too.
int dvs_texel_level(ivec3 texel) { return texel.z / voxel_resolution(); }

vec3 dvs_texel_center(ivec3 texel, int level) {
  int r = voxel_resolution();
  ivec3 wrapped = ivec3(texel.xy, texel.z - level * r);
  ivec3 window_voxel = (wrapped - voxel_clipmap.levels[level].origin_voxel.xyz) & ivec3(r - 1);
  return voxel_level_min(level) + (vec3(window_voxel) + 0.5) * voxel_size(level);
}

// Opacity (alpha) of `volume` (a clipmap such as voxel.albedo) at a point of `level`,
// interpolated trilinearly between voxel centres; voxels outside the window count as empty.
float dvs_opacity(sampler3D volume, vec3 relative_position, int level) {
  int r = voxel_resolution();
  vec3 c = voxel_window_coord(relative_position, level) - 0.5;
  ivec3 base = ivec3(floor(c));
  vec3 f = c - vec3(base);
  float sum = 0.0;
  for (int i = 0; i < 8; ++i) {
    ivec3 o = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    ivec3 v = base + o;
    if (any(lessThan(v, ivec3(0))) || any(greaterThanEqual(v, ivec3(r)))) continue;
    vec3 w3 = mix(1.0 - f, f, vec3(o));
    float a = texelFetch(volume, voxel_texel(v, level), 0).a;
    sum += w3.x * w3.y * w3.z * a;
  }
  return clamp(sum, 0.0, 1.0);
}

// Villegas §2.1: the cosine term of a voxel with averaged normal `n` (any length) towards the
// unit light direction `l`. Each axis contributes the face of the voxel that the normal's sign
// selects, weighted by the squared normal component; for an axis-aligned normal it is exactly
// max(dot(n, l), 0). Where the faces cancelled (n ~ 0, a thin wall) the voxel holds two
// opposite faces per axis of which one faces the light: a third per axis, half lit.
float dvs_normal_weighted_cosine(vec3 n, vec3 l) {
  float len2 = dot(n, n);
  if (!(len2 >= 1e-6) || isinf(len2)) {
    return (abs(l.x) + abs(l.y) + abs(l.z)) * (0.5 / 3.0);
  }
  vec3 unit = n * inversesqrt(len2);
  vec3 faces = mix(max(-l, vec3(0.0)), max(l, vec3(0.0)), greaterThan(unit, vec3(0.0)));
  return dot(unit * unit, faces);
}

#endif
