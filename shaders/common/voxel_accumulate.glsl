#ifndef VOXGI_VOXEL_ACCUMULATE_GLSL
#define VOXGI_VOXEL_ACCUMULATE_GLSL
// How voxelization fragments add their values into the scratch buffer, and how the resolve
// pass turns the sums into voxel values. The scratch holds one record of `stride` uint words
// per voxel of the box being voxelized.
//
// Strategy accumulate_hdr (VOXEL_STRATEGY_HDR): integer atomic adds of fixed-point values.
// Integer addition is associative, so the sums, and the resolved voxels, are the same in every
// run whatever order the fragments come in. Emission is weighted by w, the writer's coverage of
// the voxel's cross-section (voxelize.frag); everything else is the plain mean over writers.
// Words:
//   0 count | 1-3 albedo rgb x 4096 | 4 alpha x 4096 | 5-7 normal xyz x 4096 (two's
//   complement) | 8 surface plane offset x 4096 (two's complement; voxels, along the writer's
//   normal) | with VOXEL_HAS_EMISSION: 9 sum of w x 2^20 | 10-15 emission rgb x w as 64-bit
//   fixed point x 2^24 (low word, high word per channel).
// The resolve divides the emission by max(sum of w, 1): the uncovered part of a column at an
// emitter's edge emits nothing, so an emitter's voxels send out the emitter's power, not that
// of the voxels its conservative coverage reaches (up to a voxel more on every side). The
// albedo is not weighted: in a voxel where two walls of a room meet, each wall covers part of
// the voxel and the rest lies outside the room, where no ray from inside goes; weighting made
// such corners dark (docs/voxelization.md).
// Overflow budget per voxel: 2^32 / 4096 = 1 048 576 writers of albedo or alpha 1.0;
// 2^31 / 4096 = 524 288 writers of a unit normal component; 2^64 / (65504 x 2^24) ≈ 16.8
// million writers of the largest emission (65504, the half-float maximum every writer is
// clamped to); 2^32 writers in all. A voxel gets one write per triangle overlapping it, so
// these are far beyond any real mesh. The triangles of one surface share out a column, so
// their weights add up to at most 1 per surface layer: the weight sum holds 4096 layers.
// Resolution: 1/4096 for albedo, alpha and normals, 2^-20 ≈ 1e-6 for weights (a triangle
// covering 1/1000 of a column keeps three digits), 2^-24 ≈ 6e-8 for emission (an emitter of
// 1e-5 keeps three significant digits).
//
// Strategy average_rgba8 (VOXEL_STRATEGY_RGBA8): the compare-and-swap moving average of the
// source documents, one packed RGBA8 word per attribute (rgb value, alpha = sample count).
// Words: 0 albedo | 1 normal * 0.5 + 0.5 | 2 emission. Documented limits: values are 8-bit
// LDR (emission above 1 clips), the count saturates at 255 (later writers get weight 1/256),
// the result depends on the order of the writers, and a writer gives up after
// VOXEL_CAS_MAX_TRIES failed swaps instead of spinning without bound.

#ifndef VOXEL_SCRATCH_BINDING
#define VOXEL_SCRATCH_BINDING 0
#endif

layout(std430, set = 0, binding = VOXEL_SCRATCH_BINDING) coherent buffer VoxelScratch {
  uint voxel_scratch[];
};

const float VOXEL_UNIT_SCALE = 4096.0;
const float VOXEL_EMISSION_SCALE = 16777216.0;  // 2^24
const float VOXEL_COVERAGE_SCALE = 1048576.0;   // 2^20
const uint VOXEL_HDR_WORDS = 9u;
const uint VOXEL_HDR_WORDS_WITH_EMISSION = 16u;
const uint VOXEL_RGBA8_WORDS = 3u;
const int VOXEL_CAS_MAX_TRIES = 4096;

// Stacked surfaces (parameter stacked_surfaces = front): surfaces in one voxel that face the
// same way hide each other, e.g. a light fixture a millimetre under the ceiling hides the
// ceiling from below. A first draw of the box records, per voxel and per signed axis a face can
// face (its geometric normal's dominant component), the frontmost opaque surface: a key of its
// plane's distance from the voxel centre along its normal (larger = further out, quantized to
// 1/1024 voxel) above the low 20 bits of its instance, combined by atomicMax (order-independent).
// The second draw accumulates only fragments of that instance or within 1/64 voxel of that
// plane (coplanar pieces of other objects), so the voxel holds what is seen from the side the
// surfaces face. The six words follow the strategy's words in the record.
const uint VOXEL_FRONT_WORDS = 6u;
const float VOXEL_FRONT_DEPTH_SCALE = 1024.0;
const uint VOXEL_FRONT_TOLERANCE = 16u;  // 1/64 voxel
const uint VOXEL_FRONT_INSTANCE_MASK = 0xFFFFFu;

uint voxel_front_axis(vec3 face_normal) {
  vec3 a = abs(face_normal);
  uint axis = a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
  return axis * 2u + (face_normal[axis] < 0.0 ? 1u : 0u);
}

// depth: signed distance (voxels) of the surface plane from the voxel centre along the face
// normal, within [-1, 1] for a plane that overlaps the voxel.
uint voxel_front_key(float depth, uint instance) {
  uint quantized = uint(round(clamp(depth + 1.0, 0.0, 2.0) * VOXEL_FRONT_DEPTH_SCALE));
  return (quantized << 20) | (instance & VOXEL_FRONT_INSTANCE_MASK);
}

bool voxel_front_visible(uint key, uint front) {
  if (front == 0u) return true;  // no opaque surface faces this way here
  if ((key & VOXEL_FRONT_INSTANCE_MASK) == (front & VOXEL_FRONT_INSTANCE_MASK)) return true;
  return (key >> 20) + VOXEL_FRONT_TOLERANCE >= (front >> 20);
}

// Faces (the optional faces volume, contracts/voxel_volumes.glsl): per group of writers whose
// normal leans furthest along one signed axis (voxel_front_axis), the sum of their areas in
// the voxel (voxel faces) x 2^16, of their unit normals x 4096 (two's complement) and the
// frontmost of their planes: words 5g (area), 5g + 1..3 (xyz) and 5g + 4 (the largest plane
// offset along the writer's normal, (offset + 1) x 1024 + 1 by atomicMax, 0 for none) of the
// 30 that follow the strategy's words (before the front words). A writer's area is at most
// sqrt(3) (a triangle across the voxel's diagonal), so the area sum holds some 37 000 writers;
// the normal's overflow is as for the normal.
const uint VOXEL_FACE_WORDS = 30u;
const uint VOXEL_FACE_GROUP_WORDS = 5u;
const float VOXEL_FACE_AREA_SCALE = 65536.0;
const float VOXEL_FACE_OFFSET_SCALE = 1024.0;

void voxel_accumulate_face(uint face_base, vec3 normal, float area, float plane_offset) {
  uint word = face_base + VOXEL_FACE_GROUP_WORDS * voxel_front_axis(normal);
  ivec3 n = ivec3(round(clamp(normal, -1.0, 1.0) * VOXEL_UNIT_SCALE));
  atomicAdd(voxel_scratch[word], uint(round(clamp(area, 0.0, 2.0) * VOXEL_FACE_AREA_SCALE)));
  atomicAdd(voxel_scratch[word + 1u], uint(n.x));
  atomicAdd(voxel_scratch[word + 2u], uint(n.y));
  atomicAdd(voxel_scratch[word + 3u], uint(n.z));
  float offset = clamp(plane_offset, -1.0, 1.0) + 1.0;
  atomicMax(voxel_scratch[word + 4u], uint(round(offset * VOXEL_FACE_OFFSET_SCALE)) + 1u);
}

// The frontmost plane offset of a group whose key word is `key` (0 when it has none).
float voxel_face_plane_offset(uint key) {
  return key == 0u ? 0.0 : float(key - 1u) / VOXEL_FACE_OFFSET_SCALE - 1.0;
}

// Adds a non-negative fixed-point value below 2^40 (value = x * 2^24, x <= 65504) to the
// 64-bit sum in words (low, low + 1); a carry out of the low word goes into the high word.
void voxel_add_fixed64(uint low_word, float x) {
  float high_part = floor(x / 256.0);  // x * 2^24 / 2^32
  uint high = uint(high_part);
  uint low = uint(round((x - high_part * 256.0) * VOXEL_EMISSION_SCALE));
  if (low == 0u && high == 0u) return;
  uint before = atomicAdd(voxel_scratch[low_word], low);
  uint carry = (before + low < before) ? 1u : 0u;
  if (high + carry != 0u) atomicAdd(voxel_scratch[low_word + 1u], high + carry);
}

float voxel_read_fixed64(uint low_word) {
  return (float(voxel_scratch[low_word + 1u]) * 4294967296.0 + float(voxel_scratch[low_word])) /
         VOXEL_EMISSION_SCALE;
}

// coverage: the writer's coverage of its pixel column (0..1). plane_offset: signed distance
// (voxels) from the voxel centre to the writer's surface plane, measured along `normal`.
void voxel_accumulate_hdr(uint base, float coverage, vec3 albedo, float alpha, vec3 normal,
                          float plane_offset, vec3 emission) {
  // The weight is quantized first and the emission scaled by the quantized weight, so that a
  // uniform emitter resolves exactly to its own radiance.
  float w = round(clamp(coverage, 0.0, 1.0) * VOXEL_COVERAGE_SCALE) / VOXEL_COVERAGE_SCALE;
  uvec3 a = uvec3(round(clamp(albedo, 0.0, 1.0) * VOXEL_UNIT_SCALE));
  ivec3 n = ivec3(round(clamp(normal, -1.0, 1.0) * VOXEL_UNIT_SCALE));
  atomicAdd(voxel_scratch[base], 1u);
  atomicAdd(voxel_scratch[base + 1u], a.r);
  atomicAdd(voxel_scratch[base + 2u], a.g);
  atomicAdd(voxel_scratch[base + 3u], a.b);
  atomicAdd(voxel_scratch[base + 4u], uint(round(clamp(alpha, 0.0, 1.0) * VOXEL_UNIT_SCALE)));
  atomicAdd(voxel_scratch[base + 5u], uint(n.x));
  atomicAdd(voxel_scratch[base + 6u], uint(n.y));
  atomicAdd(voxel_scratch[base + 7u], uint(n.z));
  atomicAdd(voxel_scratch[base + 8u],
            uint(int(round(clamp(plane_offset, -2.0, 2.0) * VOXEL_UNIT_SCALE))));
#ifdef VOXEL_HAS_EMISSION
  atomicAdd(voxel_scratch[base + 9u], uint(w * VOXEL_COVERAGE_SCALE));
  voxel_add_fixed64(base + 10u, emission.r * w);
  voxel_add_fixed64(base + 12u, emission.g * w);
  voxel_add_fixed64(base + 14u, emission.b * w);
#endif
}

// Moving average of `value` (0..1) into the packed word: rgb average, alpha = count / 255.
void voxel_average_rgba8(uint word, vec3 value) {
  value = clamp(value, 0.0, 1.0);
  uint expected = 0u;
  uint desired = packUnorm4x8(vec4(value, 1.0 / 255.0));
  for (int attempt = 0; attempt < VOXEL_CAS_MAX_TRIES; ++attempt) {
    uint found = atomicCompSwap(voxel_scratch[word], expected, desired);
    if (found == expected) return;
    expected = found;
    vec4 current = unpackUnorm4x8(found);
    float count = round(current.a * 255.0);
    vec3 average = (current.rgb * count + value) / (count + 1.0);
    desired = packUnorm4x8(vec4(average, min(count + 1.0, 255.0) / 255.0));
  }
}

#endif
