#version 460
// Voxelization resolve: turns the scratch sums of one box into the voxel volumes (toroidal
// clipmap texels, see contracts/voxel_clipmap.glsl), and zeroes the scratch records it read so the
// next box starts from zero.

#include "lib/common.glsl"
#include "contracts/voxel_volumes.glsl"
#include "common/voxel_accumulate.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(set = 0, binding = 1, rgba8) uniform writeonly image3D albedo_volume;
layout(set = 0, binding = 2, rgba16f) uniform writeonly image3D normal_volume;
#ifdef VOXEL_HAS_EMISSION
layout(set = 0, binding = 3, rgba16f) uniform writeonly image3D emission_volume;
#endif

#ifdef VOXEL_FACES
layout(set = 0, binding = 4, rgba32ui) uniform writeonly uimage3D faces_volume;
#endif

layout(push_constant) uniform VoxelResolvePush {
  ivec4 box_min;  // xyz: window voxels; w: level
  ivec4 box_max;  // xyz: exclusive; w: R
  ivec4 origin;   // xyz: the level's window origin (voxels from the anchor); w: words per voxel
} resolve;

void main() {
  ivec3 local = ivec3(gl_GlobalInvocationID);
  ivec3 extent = resolve.box_max.xyz - resolve.box_min.xyz;
  if (any(greaterThanEqual(local, extent))) return;
  int r = resolve.box_max.w;
  ivec3 wrapped = ((resolve.box_min.xyz + local + resolve.origin.xyz) % r + r) % r;
  ivec3 texel = ivec3(wrapped.xy, wrapped.z + resolve.box_min.w * r);
  uint stride = uint(resolve.origin.w);
  uint base = uint((local.z * extent.y + local.y) * extent.x + local.x) * stride;

  vec4 albedo = vec4(0.0), normal = vec4(0.0), emission = vec4(0.0);
  uvec4 faces = uvec4(0u);
#ifdef VOXEL_STRATEGY_RGBA8
  vec4 packed_albedo = unpackUnorm4x8(voxel_scratch[base]);
  if (packed_albedo.a > 0.0) {
    albedo = vec4(packed_albedo.rgb, 1.0);
    normal = vec4(unpackUnorm4x8(voxel_scratch[base + 1u]).rgb * 2.0 - 1.0, 1.0);
#ifdef VOXEL_HAS_EMISSION
    emission = vec4(unpackUnorm4x8(voxel_scratch[base + 2u]).rgb, 0.0);
#endif
  }
#else
  uint count = voxel_scratch[base];
  if (count > 0u) {
    float scale = 1.0 / (VOXEL_UNIT_SCALE * float(count));
    albedo = vec4(vec3(voxel_scratch[base + 1u], voxel_scratch[base + 2u], voxel_scratch[base + 3u]),
                  float(voxel_scratch[base + 4u])) * scale;
    vec3 n = vec3(int(voxel_scratch[base + 5u]), int(voxel_scratch[base + 6u]),
                  int(voxel_scratch[base + 7u])) * scale;
    // An average of unit vectors is at most unit length; rounding may push it a hair over.
    float len2 = dot(n, n);
    float plane_offset = float(int(voxel_scratch[base + 8u])) * scale;
    normal = vec4(len2 > 1.0 ? n * inversesqrt(len2) : n, voxel_encode_plane_offset(plane_offset));
#ifdef VOXEL_FACES
#ifdef VOXEL_HAS_EMISSION
    uint face_base = base + VOXEL_HDR_WORDS_WITH_EMISSION;
#else
    uint face_base = base + VOXEL_HDR_WORDS;
#endif
    // Shares of the surfaces' area in the voxel.
    float total_area = 0.0;
    for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
      total_area += float(voxel_scratch[face_base + VOXEL_FACE_GROUP_WORDS * uint(g)]);
    }
    for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
      uint w = face_base + VOXEL_FACE_GROUP_WORDS * uint(g);
      uint area = voxel_scratch[w];
      if (area == 0u) continue;
      vec3 sum = vec3(int(voxel_scratch[w + 1u]), int(voxel_scratch[w + 2u]),
                      int(voxel_scratch[w + 3u]));
      // The sum leans along the group's axis by construction, so it is never zero.
      vec3 axis = vec3(0.0);
      axis[g >> 1] = (g & 1) == 0 ? 1.0 : -1.0;
      vec3 direction = dot(sum, sum) > 0.0 ? normalize(sum) : axis;
      faces = voxel_pack_face(faces, g, direction, float(area) / total_area,
                              voxel_face_plane_offset(voxel_scratch[w + 4u]));
    }
#endif
#ifdef VOXEL_HAS_EMISSION
    // The uncovered part of an emitter's edge voxel emits nothing: divided by the sum of the
    // coverage weights or 1, whichever is larger (voxel_accumulate.glsl).
    float coverage = float(voxel_scratch[base + 9u]) / VOXEL_COVERAGE_SCALE;
    emission.rgb = vec3(voxel_read_fixed64(base + 10u), voxel_read_fixed64(base + 12u),
                        voxel_read_fixed64(base + 14u)) /
                   max(coverage, 1.0);
#endif
  }
#endif
  albedo = clamp(albedo, 0.0, 1.0);
  imageStore(albedo_volume, texel, albedo);
  imageStore(normal_volume, texel, normal);
#ifdef VOXEL_FACES
  imageStore(faces_volume, texel, faces);
#endif
#ifdef VOXEL_HAS_EMISSION
  imageStore(emission_volume, texel, vec4(sanitize_radiance(emission.rgb), 0.0));
#endif
  // A voxel nobody wrote has an all-zero record already (word 0 is the count, or the packed
  // albedo that every writer sets).
  if (normal.w > 0.0) {
    for (uint w = 0u; w < stride; ++w) voxel_scratch[base + w] = 0u;
  }
}
