#version 460
#extension GL_GOOGLE_include_directive : require
// vct.filter: builds the filtered volumes the cone tracer reads (layout: contracts/cone_trace.glsl)
// from the radiance clipmap (rgb = outgoing radiance, a = opacity, not premultiplied).
//   STAGE_LEVEL: mip 0 of one clipmap level. Where the next finer level covers a voxel's eight
//     children, the voxel is their filter (levels agree); elsewhere the injected radiance,
//     premultiplied, with (LEVEL_COVERAGE) the opacity (along each axis when anisotropic) that
//     the filter would have given a surface voxelized at the finest level's thickness, and
//     (anisotropic, FACE_FACING) in each direction the light its surfaces show that way, from
//     their face groups and (LIGHT_SHARES) each group's share of the light (directional_light).
//     Levels run finest first, so level l-1 is final when level l reads it.
//   STAGE_MIP: mip m of every level from mip m-1 of the same level (texel t <- 2t + {0,1}^3).
// Isotropic: box filter of the 8 children. Anisotropic (ANISOTROPIC=1): per direction, the
// front-to-back composite of each child pair along the axis, averaged over the 4 columns.
// FRONT_LIGHT (anisotropic, with the faces): each directional volume holds only the light of the
// face groups facing its direction of travel, and the two facing volumes (facing_pos: +X, +Y,
// +Z in channels x, y, z; facing_neg: -X, -Y, -Z) the share of the opacity lying across it,
// premultiplied and composited like the light (front_light; contracts/cone_trace.glsl reads
// the light over that share).
// NaN/Inf and out-of-range values are scrubbed when read. The filter works on, and stores,
// premultiplied radiance and opacity (contracts/vct_volume_encoding.glsl).
#include "lib/common.glsl"
#include "contracts/vct_volume_encoding.glsl"
#include "contracts/voxel_volumes.glsl"
#define VOXEL_CLIPMAP_SET 0
#define VOXEL_CLIPMAP_BINDING 0
#include "contracts/voxel_clipmap.glsl"

#ifndef ANISOTROPIC
#define ANISOTROPIC 0
#endif
#if ANISOTROPIC
#define VOLUMES 6
#else
#define VOLUMES 1
#endif
#ifndef LEVEL_COVERAGE
#define LEVEL_COVERAGE 0
#endif

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(set = 0, binding = 1) uniform sampler3D radiance;  // mip 0 read with texelFetch
#if LEVEL_COVERAGE
// The voxels' averaged normals (contracts/voxel_volumes.glsl), read with texelFetch.
layout(set = 0, binding = 14) uniform sampler3D voxel_normal;
#endif
#ifndef FACE_FACING
#define FACE_FACING 0
#endif
#if FACE_FACING
layout(set = 0, binding = 15) uniform usampler3D voxel_faces;
#endif
// Source (mip m-1, or mip 0 of the finer level) and destination views of each volume.
layout(set = 0, binding = 2, rgba16f) uniform image3D src0;
layout(set = 0, binding = 3, rgba16f) uniform image3D dst0;
#if ANISOTROPIC
layout(set = 0, binding = 4, rgba16f) uniform image3D src1;
layout(set = 0, binding = 5, rgba16f) uniform image3D dst1;
layout(set = 0, binding = 6, rgba16f) uniform image3D src2;
layout(set = 0, binding = 7, rgba16f) uniform image3D dst2;
layout(set = 0, binding = 8, rgba16f) uniform image3D src3;
layout(set = 0, binding = 9, rgba16f) uniform image3D dst3;
layout(set = 0, binding = 10, rgba16f) uniform image3D src4;
layout(set = 0, binding = 11, rgba16f) uniform image3D dst4;
layout(set = 0, binding = 12, rgba16f) uniform image3D src5;
layout(set = 0, binding = 13, rgba16f) uniform image3D dst5;
#endif

#ifndef FRONT_LIGHT
#define FRONT_LIGHT 0
#endif
#if FRONT_LIGHT
#if !(ANISOTROPIC && FACE_FACING)
#error FRONT_LIGHT needs the six directional volumes and the voxels' faces
#endif
layout(set = 0, binding = 17, rgba16f) uniform image3D src_facing_pos;
layout(set = 0, binding = 18, rgba16f) uniform image3D dst_facing_pos;
layout(set = 0, binding = 19, rgba16f) uniform image3D src_facing_neg;
layout(set = 0, binding = 20, rgba16f) uniform image3D dst_facing_neg;

// Volume `volume`'s facing share (premultiplied) at a source texel.
float load_facing(int volume, ivec3 texel) {
  vec4 v = (volume & 1) == 0 ? imageLoad(src_facing_pos, texel) : imageLoad(src_facing_neg, texel);
  float c = v[volume / 2];
  return isnan(c) || isinf(c) ? 0.0 : clamp(c, 0.0, 1.0);
}

// The six volumes' facing shares, by volume index, into the two facing volumes.
void store_facing(ivec3 texel, float facing[6]) {
  imageStore(dst_facing_pos, texel, vec4(facing[0], facing[2], facing[4], 0.0));
  imageStore(dst_facing_neg, texel, vec4(facing[1], facing[3], facing[5], 0.0));
}
#endif

layout(push_constant) uniform Push {
  int stage;  // 0: level mip 0, 1: mip of all levels
  int level;  // STAGE_LEVEL: the level written
  int mip;    // STAGE_MIP: the mip written
  int pad;
} pc;

vec4 scrub(vec4 v) {
  float a = isnan(v.a) || isinf(v.a) ? 0.0 : clamp(v.a, 0.0, 1.0);
  return vec4(sanitize_radiance(v.rgb), a);
}

vec4 load_src(int volume, ivec3 texel) {
  vec4 v;
#if ANISOTROPIC
  switch (volume) {
    case 0: v = imageLoad(src0, texel); break;
    case 1: v = imageLoad(src1, texel); break;
    case 2: v = imageLoad(src2, texel); break;
    case 3: v = imageLoad(src3, texel); break;
    case 4: v = imageLoad(src4, texel); break;
    default: v = imageLoad(src5, texel); break;
  }
#else
  v = imageLoad(src0, texel);
#endif
  return vct_decode_volume(scrub(v));
}

void store_dst(int volume, ivec3 texel, vec4 v) {
  v = vct_encode_volume(scrub(v));
#if ANISOTROPIC
  switch (volume) {
    case 0: imageStore(dst0, texel, v); break;
    case 1: imageStore(dst1, texel, v); break;
    case 2: imageStore(dst2, texel, v); break;
    case 3: imageStore(dst3, texel, v); break;
    case 4: imageStore(dst4, texel, v); break;
    default: imageStore(dst5, texel, v); break;
  }
#else
  imageStore(dst0, texel, v);
#endif
}

// Front-to-back composite of premultiplied samples, `front` nearer to the viewer.
vec4 over(vec4 front, vec4 back) {
  return vec4(front.rgb + (1.0 - front.a) * back.rgb, front.a + (1.0 - front.a) * back.a);
}

// The window coordinate, in level - 1, of the first of the eight children of the voxel at
// window coordinate `window` of `level` (> 0).
ivec3 first_finer_child(int level, ivec3 window) {
  ivec3 world = window + voxel_clipmap.levels[level].origin_voxel.xyz;
  return world * 2 - voxel_clipmap.levels[level - 1].origin_voxel.xyz;
}

// True where the next finer level holds all eight children of that voxel: there mip 0 of
// `level` is their filter; elsewhere it holds its own injected light.
bool finer_level_covers(int level, ivec3 window) {
  if (level == 0 || !voxel_level_valid(level - 1) || !voxel_level_valid(level)) return false;
  ivec3 first = first_finer_child(level, window);
  return all(greaterThanEqual(first, ivec3(0))) &&
         all(lessThan(first + 1, ivec3(voxel_resolution())));
}

#if FACE_FACING && ANISOTROPIC
#ifndef LIGHT_SHARES
#define LIGHT_SHARES 0
#endif
#if LIGHT_SHARES
layout(set = 0, binding = 16) uniform usampler3D light_shares;
#endif

// A voxel's face groups as directional_light needs them, unpacked once for all six volumes:
// normals, area shares and light shares (contracts/voxel_volumes.glsl; the area shares where
// the injection wrote none), by group index. count 0: no faces.
struct OwnFaces {
  vec3 normals[VOXEL_FACE_GROUPS];
  float area[VOXEL_FACE_GROUPS];
  float light[VOXEL_FACE_GROUPS];
  int count;
};

OwnFaces own_faces(ivec3 texel) {
  OwnFaces f;
  f.count = voxel_faces_unpack(texelFetch(voxel_faces, texel, 0), f.normals, f.area);
  bool lit = false;
#if LIGHT_SHARES
  lit = voxel_light_shares_unpack(texelFetch(light_shares, texel, 0).r, f.light);
#endif
  if (!lit) f.light = f.area;
  return f;
}

// A voxel's face groups projected on `volume`'s axis t: the area shares towards a cone
// travelling along t (n_g.t < 0), away from it, and seen edge-on (the rest of each group's
// area), with the light the groups towards it show (front) and that plus their edge-on light
// (shown).
struct FaceProjection {
  float towards, away, edge, front, shown;
};

FaceProjection project_faces(OwnFaces f, int volume) {
  int axis = volume / 2;
  float travel = (volume & 1) == 0 ? 1.0 : -1.0;
  FaceProjection p = FaceProjection(0.0, 0.0, 0.0, 0.0, 0.0);
  for (int g = 0; g < VOXEL_FACE_GROUPS; ++g) {
    float s = f.area[g];
    if (s <= 0.0) continue;
    float c = f.normals[g][axis] * travel;
    float projected = abs(c);
    if (c < 0.0) {
      p.towards += s * projected;
      p.front += f.light[g] * projected;
      p.shown += f.light[g] * projected;
    } else {
      p.away += s * projected;
    }
    p.edge += s * (1.0 - projected);
    p.shown += f.light[g] * (1.0 - projected);
  }
  return p;
}

// How bright a voxel that holds its own injected light looks to a cone travelling along
// `volume`'s axis t, relative to its mean radiance (the injected value): from its face groups'
// normals n_g, area shares s_g and light shares l_g (OwnFaces). Along t a group shows the
// part |n_g.t| of its area towards the cone (n_g.t < 0: T in all) or away from it (A), and
// keeps the rest of its light seen edge-on (E): a cone travelling along x and down reads a
// floor through both its x and its -y volume, and the floor must look as bright in both
// (halving edge-on surfaces made every view 15-30 points dark; docs/error-budget.md). Each
// face towards the cone hides as much back area as its own, so the voxel's footprint is
// max(T, A) + E, and the fronts send their light over it:
//   factor = (sum over fronts of l_g |n_g.t| + sum of l_g (1 - |n_g.t|)) / (max(T, A) + E).
// A sunlit floor's voxels thus send nothing down through it and a wall's nothing out of its
// back; a thin wall lit on one face sends that face's light (twice the voxel's mean) towards
// its lit side and none through; a voxel whose groups are lit alike is never brighter than its
// mean. The cone tracer's facing test (contracts/cone_trace.glsl) refines this between the
// axes at the finest level's mip 0.
float directional_light(OwnFaces f, int volume) {
  if (f.count == 0) return 1.0;
  FaceProjection p = project_faces(f, volume);
  float footprint = max(p.towards, p.away) + p.edge;
  return footprint > 1e-6 ? p.shown / footprint : 0.0;
}

#if FRONT_LIGHT
// The front-light form of directional_light: (light, facing share) relative to the voxel's
// mean radiance and opacity. Only the groups facing the cone (n_g.t < 0) send light, each
// its own over its projected area; the share is the part of the voxel's footprint that lies
// across the axis, max(T, A) / (max(T, A) + E) with T, A, E as in directional_light. A cone
// reading the three axes' light over their shares (contracts/cone_trace.glsl) sees a plane's
// full radiance from any direction in front of it, through every mip and level, and none from
// behind: the edge-on light directional_light keeps is what let cones rising from below read
// sunlit floors and ledges at coarse mips (docs/error-budget.md, thirty-seventh round).
vec2 front_light(OwnFaces f, int volume) {
  if (f.count == 0) return vec2(1.0);
  FaceProjection p = project_faces(f, volume);
  float across = max(p.towards, p.away);
  float footprint = across + p.edge;
  return footprint > 1e-6 ? vec2(p.front, across) / footprint : vec2(0.0);
}
#endif
#endif

// The filtered value for `volume` from its 8 children's texels, ordered x fastest (child i
// has offset (i & 1, (i >> 1) & 1, (i >> 2) & 1)).
// FRONT_LIGHT: `facing` is the volume's facing share composited alike.
vec4 filter_children(int volume, ivec3 child[8], out float facing) {
  facing = 0.0;
  vec4 c[8];
  for (int i = 0; i < 8; ++i) c[i] = load_src(volume, child[i]);
#if FRONT_LIGHT
  float f[8];
  for (int i = 0; i < 8; ++i) f[i] = load_facing(volume, child[i]);
#endif
#if ANISOTROPIC
  // Volume 2k+s looks along axis k, s = 0 positive (lower coordinate in front), 1 negative.
  int axis = volume / 2;
  bool positive = (volume & 1) == 0;
  int stride = axis == 0 ? 1 : (axis == 1 ? 2 : 4);
  vec4 sum = vec4(0.0);
  for (int i = 0; i < 8; ++i) {
    if ((i & stride) != 0) continue;  // i is the lower child of its pair along the axis
    vec4 lower = c[i];
    vec4 upper = c[i + stride];
    sum += positive ? over(lower, upper) : over(upper, lower);
#if FRONT_LIGHT
    float f_lower = f[i], f_upper = f[i + stride];
    facing += positive ? f_lower + (1.0 - lower.a) * f_upper : f_upper + (1.0 - upper.a) * f_lower;
#endif
  }
  facing *= 0.25;
  return sum * 0.25;
#else
  vec4 sum = vec4(0.0);
  for (int i = 0; i < 8; ++i) sum += c[i];
  return sum * 0.125;
#endif
}

#if LEVEL_COVERAGE
// The opacity of a voxel of a coarser level (level > 0) that no finer level covers, made to
// agree with what the filter gives where one does. The surfaces are voxelized one finest voxel
// thick; filtered up l levels, a plane crossing the voxel stays opaque to rays across it but
// covers only 1/2^l of the columns that run along it (anisotropic), or of the voxel
// (isotropic, for a plane on an axis; one of unit normal n touches about (|n_x| + |n_y| +
// |n_z|) / max_k |n_k| times as many fine voxels). Injected directly at level l it would be
// opaque from every side, 2^l times thicker than its filtered twin next to it. A voxel whose
// writers' normals cancel (|n| < VOXEL_NORMAL_MIN_LENGTH) or that has no normal is left opaque
// from every side. Returns the coverage along x, y, z (isotropic: the
// same in all three).
vec3 level_coverage(vec4 normal_texel, int level) {
  vec3 n = normal_texel.xyz;
  if (level == 0 || !voxel_normal_occupied(normal_texel) || any(isnan(n)) ||
      dot(n, n) < VOXEL_NORMAL_MIN_LENGTH * VOXEL_NORMAL_MIN_LENGTH) {
    return vec3(1.0);
  }
  vec3 across = abs(normalize(n));
  float fine = exp2(-float(level));
#if ANISOTROPIC
  // Axis k sees |n_k| of the plane across and the rest along.
  return across + (1.0 - across) * fine;
#else
  float largest = max(across.x, max(across.y, across.z));
  return vec3(min(1.0, fine * (across.x + across.y + across.z) / largest));
#endif
}
#endif

void main() {
  int r = voxel_resolution();
  int levels = voxel_level_count();
  ivec3 id = ivec3(gl_GlobalInvocationID);
  if (pc.stage == 0) {
    if (any(greaterThanEqual(id, ivec3(r)))) return;
    int level = pc.level;
    ivec3 texel = voxel_texel(id, level);
    if (finer_level_covers(level, id)) {
      ivec3 first = first_finer_child(level, id);
      ivec3 child[8];
      for (int i = 0; i < 8; ++i) {
        ivec3 offset = ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
        child[i] = voxel_texel(first + offset, level - 1);
      }
      float facing[6];
      for (int v = 0; v < VOLUMES; ++v) store_dst(v, texel, filter_children(v, child, facing[v]));
#if FRONT_LIGHT
      store_facing(texel, facing);
#endif
    } else {
      // The voxel's own injected light, sent (given its faces) the ways its surfaces face;
      // every composite above is built from these.
      vec4 injected = scrub(texelFetch(radiance, texel, 0));
      bool lit = any(greaterThan(injected.rgb, vec3(0.0)));
      vec3 coverage = vec3(1.0);
#if LEVEL_COVERAGE
      coverage = level_coverage(texelFetch(voxel_normal, texel, 0), level);
#endif
#if FACE_FACING && ANISOTROPIC
      OwnFaces faces;
      faces.count = 0;
#if FRONT_LIGHT
      // Unlit voxels too: their share of the footprint darkens what is read through them.
      if (injected.a > 0.0) faces = own_faces(texel);
      float facing[6];
#else
      if (lit) faces = own_faces(texel);
#endif
#endif
      for (int v = 0; v < VOLUMES; ++v) {
        float a = injected.a * coverage[v / 2];
        vec3 rgb = injected.rgb;
#if FRONT_LIGHT
        vec2 front = front_light(faces, v);
        rgb *= front.x;
        facing[v] = front.y * a;
#elif FACE_FACING && ANISOTROPIC
        if (lit) rgb *= directional_light(faces, v);
#endif
        store_dst(v, texel, vec4(rgb * a, a));
      }
#if FRONT_LIGHT
      store_facing(texel, facing);
#endif
    }
    return;
  }
  int rm = r >> pc.mip;
  int rs = rm * 2;  // source mip edge
  if (any(greaterThanEqual(id, ivec3(rm, rm, rm * levels)))) return;
  int level = id.z / rm;
  ivec3 local = ivec3(id.xy, id.z - level * rm);
  ivec3 child[8];
  for (int i = 0; i < 8; ++i) {
    ivec3 c = local * 2 + ivec3(i & 1, (i >> 1) & 1, (i >> 2) & 1);
    child[i] = ivec3(c.xy, c.z + level * rs);
  }
  float facing[6];
  for (int v = 0; v < VOLUMES; ++v) store_dst(v, id, filter_children(v, child, facing[v]));
#if FRONT_LIGHT
  store_facing(id, facing);
#endif
}
