#ifndef VOXGI_CONE_TRACE_GLSL
#define VOXGI_CONE_TRACE_GLSL
// Contract: voxel cone tracing through the filtered radiance clipmap (vct.filter's outputs),
// the reading side of that data shared by every family that gathers from it (vct.cone_trace,
// vct.cone_trace_specular, dvs's per-voxel bounce). C++ twin (slot names, sampler):
// passes/contracts/filtered_volumes.hpp. docs/vct.md derives the weights and corrections.
//
// STORAGE (written by vct.filter, read here)
//   Every filtered volume is a clipmap with the addressing of contracts/voxel_clipmap.glsl (same R,
//   L, toroidal origin) and a full mip chain: mip m holds, per level l, R>>m voxels per edge at
//   z in [l*(R>>m), (l+1)*(R>>m)). Texel m of world voxel w is (w >> m) mod (R >> m).
//   The form of contracts/vct_volume_encoding.glsl: premultiplied radiance and opacity of one
//   voxel length at that level and mip. The tracer filters it across a cone's travel as stored
//   and along the travel as optical depth (vct_fetch_along; that file says why).
//   Mip m of level l is the filter of mip m-1; mip 0 of level l > 0 is,
//   where level l-1 covers it, the filter of level l-1's mip 0 (so the levels agree), and
//   elsewhere the injected radiance of level l.
//   Isotropic mode (VCT_ANISOTROPIC 0): one volume, the box filter of the 8 children.
//   Anisotropic mode (VCT_ANISOTROPIC 1): six volumes, index 0..5 = +X, -X, +Y, -Y, +Z, -Z.
//   Volume +X is what a cone travelling in +X sees: each voxel is the average over the four
//   child columns of the front-to-back composite along +X (children at lower x in front).
//   Voxels with no finer data (level 0 mip 0, the part of a level no finer level covers) hold
//   the injected value in all six; where vct.filter has the voxels' faces, in volume d the
//   light their surfaces show a cone travelling along d (each face group's own light where the
//   injection wrote light shares: a thin wall's lit face's towards its lit side only, none
//   through it); where vct.filter has the voxel normals, the voxels of a
//   coarser level l > 0 among them hold the opacity that filtering a surface voxelized at the
//   finest level would have given them (along axis k a (|n_k| + (1 - |n_k|) / 2^l); isotropic:
//   the fraction of fine voxels the surface fills).
//   Front-light mode (VCT_FRONT_LIGHT 1, anisotropic): volume d holds only the light of the face
//   groups facing a cone travelling along d, and two more volumes, facing_pos (+X, +Y, +Z in
//   x, y, z) and facing_neg (-X, -Y, -Z), hold per direction the share of the opacity lying
//   across it, premultiplied and filtered like the light (vct_fetch_directional reads the
//   light over that share).
//
// BINDINGS (the includer provides them)
//   Include contracts/voxel_clipmap.glsl first (the clipmap info buffer). Define VCT_VOLUME_SET and
//   VCT_VOLUME_BINDING (defaults 0 and 1) and VCT_ANISOTROPIC (default 0); the volumes are
//   one array binding `sampler3D vct_volumes[1, 6, or 8 with VCT_FRONT_LIGHT]`, each combined
//   with a sampler that is
//   LINEAR, address mode REPEAT (the toroidal wrap in x and y; z is interpolated here by hand
//   because levels are stacked in z), whole-mip lods (mipmap mode NEAREST suffices) and no
//   anisotropic filtering, which has no meaning for explicit lods. contracts::VolumeSampler
//   is exactly that; gpu::SamplerKind::LinearRepeatMipmapped also works but adds anisotropy
//   where the device has it.
//   Optionally define VCT_FACING_NORMALS as the name of a sampler3D over the voxel normals
//   (contracts/voxel_volumes.glsl, same clipmap layout, sampled like the volumes): then a
//   sample at mip 0 of the finest level present sends its light only towards the side its
//   surfaces face (vct_facing below).
//
// API
//   vct_sample(p, dir, lod)            filtered volume value (stored form) at a point
//   vct_sample_step(p, dir, lod, ...)  the same for a cone's step, refined at surfaces
//   vct_trace_cone(cone, settings)     front-to-back accumulation along one cone
//   vct_diffuse_cone(i, n, rot, ring, ...)  the i-th of n diffuse cones (tangent space) + weight
//   vct_diffuse_irradiance(...)        irradiance E over the hemisphere of a normal, and AO
//   vct_specular_tan_half_angle(r)     cone aperture for a GGX perceptual roughness
// Positions are anchor-relative (voxel_relative(world)); distances in metres.

#include "contracts/vct_volume_encoding.glsl"
#include "contracts/voxel_volumes.glsl"

#ifndef VCT_VOLUME_SET
#define VCT_VOLUME_SET 0
#endif
#ifndef VCT_VOLUME_BINDING
#define VCT_VOLUME_BINDING 1
#endif
#ifndef VCT_ANISOTROPIC
#define VCT_ANISOTROPIC 0
#endif
// 1 where the volumes may hold a level stored without the wrap (contracts::
// unwrapped_windows_define: one level, which stays put unless it follows the camera); 0 leaves
// the wrapped path alone, which lavapipe runs some 1.2x slower with the check in it.
#ifndef VCT_UNWRAPPED_WINDOWS
#define VCT_UNWRAPPED_WINDOWS 0
#endif
// 1: the front-light mode (contracts::front_light_define): vct_volumes holds eight samplers,
// the six directional volumes, then facing_pos and facing_neg (vct_fetch_directional).
#ifndef VCT_FRONT_LIGHT
#define VCT_FRONT_LIGHT 0
#endif
#if VCT_FRONT_LIGHT && !VCT_ANISOTROPIC
#error VCT_FRONT_LIGHT needs VCT_ANISOTROPIC
#endif
#if VCT_ANISOTROPIC && VCT_FRONT_LIGHT
#define VCT_VOLUME_COUNT 8
#elif VCT_ANISOTROPIC
#define VCT_VOLUME_COUNT 6
#else
#define VCT_VOLUME_COUNT 1
#endif
// Hard cap on the steps of one cone, so that no parameter combination can hang the GPU.
#define VCT_MAX_STEPS 512
// Most lanes of a cone (vct_trace_cone, VctTraceSettings.lanes): thin sub-cones across its
// width.
#define VCT_MAX_LANES 8
// A cone stops once it is this opaque: the rest would add less than 1% of its radiance.
#define VCT_OPACITY_THRESHOLD 0.99
// How far inside a level's window (in its voxels) a sample must lie: there the trilinear
// footprint of mip 0 stays inside the window instead of wrapping to the opposite face, and the
// outermost layer of voxels is still seen whole (its centres are half a voxel in). Cones end
// where no level holds them so. (A margin of one voxel hid that layer: a ceiling and its light
// in a 32^3 window's last layer took 40-66% of the Cornell box's indirect light with them.)
#define VCT_WINDOW_MARGIN 0.5
// Most mips of a volume: log2 of the largest voxel resolution (common.voxelize allows 1024).
#define VCT_MAX_MIP 10
// The level a cone of diameter D reads: mip m's voxels (edge V) are box filters of width V read
// through the trilinear tent of half width V, a kernel of standard deviation V / 2 along each
// axis; the cone's cross-section, a disc of diameter D, has D / 4. So the level whose kernel is
// as wide as the cone is V = D / 2, one level finer than V = D. (Read at V = D, as cone tracers
// usually do, a sample reached a cone radius beyond the cone: an area light behind the Cornell
// boxes' blocks lit the floor at their base through cones passing beside them, at every voxel
// resolution and cone count; docs/error-budget.md, thirtieth round.) Lanes (vct_trace_cone)
// share the cross-section and are read half a level finer again per doubling of their number.
#define VCT_FOOTPRINT_LOD_BIAS 1.0
// Widest cone aperture (half angle 60 degrees): wider cones jump to the coarsest mips at once.
#define VCT_MAX_TAN_HALF_ANGLE 1.7320508

layout(set = VCT_VOLUME_SET, binding = VCT_VOLUME_BINDING) uniform sampler3D
    vct_volumes[VCT_VOLUME_COUNT];

const float VCT_PI = 3.14159265358979323846;

// Continuous texel coordinate of anchor-relative p in `level`'s mip `mip` (texel centres at
// i + 0.5; x and y before the toroidal wrap, z within the level's slab of r slices).
vec3 vct_texel_coord(vec3 p, int level, int mip) {
  int r = voxel_resolution() >> mip;
  ivec3 origin = voxel_clipmap.levels[level].origin_voxel.xyz;
  // Continuous world-voxel coordinate at this mip, split into an integer part kept exact and
  // a small fraction, so that scenes far from the origin keep precision.
  ivec3 origin_mip = origin >> mip;  // arithmetic shift: floor division for negatives too
  vec3 remainder = vec3(origin - (origin_mip << mip));
  vec3 fraction = (voxel_window_coord(p, level) + remainder) / float(1 << mip);
  ivec3 base = origin_mip & (r - 1);  // floor modulo: r is a power of two
  return vec3(base) + fraction;
}

// One layer of texels across a cone's travel along `axis`: texel coordinate `texel`
// (vct_texel_coord) with the axis's coordinate at that layer's centre, filtered across (the
// sampler in x and y, z by hand between two slices of the level). A level stored without the
// wrap (voxel_level_unwrapped: windows that stay put) holds nothing beyond its window: there
// the coordinate is clamped to the outermost texel centres and the result scaled by the
// filter's weight inside, which is the trilinear filter with empty texels outside, exactly and
// for free. (Wrapped, a footprint there would read the window's opposite face, so cones near a
// fitted volume's walls kept to fine mips: relMSE 4-8% higher on the Cornell boxes' dense
// levels and dvs; docs/error-budget.md, thirteenth round.)
vec4 vct_fetch_layer(sampler3D volume, vec3 texel, int level, int mip) {
  int r = voxel_resolution() >> mip;
  float inside = 1.0;
#if VCT_UNWRAPPED_WINDOWS
  bool unwrapped = voxel_level_unwrapped(level);
#else
  const bool unwrapped = false;
#endif
  if (unwrapped) {
    vec3 weight = clamp(texel + 0.5, 0.0, 1.0) * clamp(float(r) + 0.5 - texel, 0.0, 1.0);
    inside = weight.x * weight.y;
    texel.xy = clamp(texel.xy, vec2(0.5), vec2(float(r) - 0.5));
  }
  float z = texel.z - 0.5;
  float z0 = floor(z);
  float wz = z - z0;
  int s0 = int(z0) & (r - 1);
  vec2 xy = texel.xy / float(r);  // REPEAT wraps
  float depth = float(r * voxel_level_count());
  // Slices beyond an unwrapped window are empty: z0 = -1 or z0 + 1 = r.
  float wa = 1.0 - wz, wb = wz;
  if (unwrapped) {
    wa *= float(z0 >= 0.0) * inside;
    wb *= float(z0 + 1.0 < float(r)) * inside;
  }
  vec4 a = textureLod(volume, vec3(xy, (float(level * r + s0) + 0.5) / depth), float(mip));
  if (!(wz > 0.0)) return wa * a;
  int s1 = (s0 + 1) & (r - 1);
  vec4 b = textureLod(volume, vec3(xy, (float(level * r + s1) + 0.5) / depth), float(mip));
  return wa * a + wb * b;
}

// One level and mip of a volume at anchor-relative position p, trilinear as the hardware
// filters (the voxel normals of the facing test).
vec4 vct_fetch(sampler3D volume, vec3 p, int level, int mip) {
  return vct_fetch_layer(volume, vct_texel_coord(p, level, mip), level, mip);
}

// vct_mix_along mixes the two layers a, b (optical-depth form) at weight w of b; ca and cb are
// one more channel of the same form (the facing share of the front-light mode), mixed alike
// into c.
vec4 vct_mix_along(vec4 a, vec4 b, float ca, float cb, float w, bool forward, out float c) {
  float tau = mix(a.a, b.a, w);
  vec4 front = forward ? a : b;
  vec4 back = forward ? b : a;
  float front_weight = forward ? 1.0 - w : w;
  float back_weight = (1.0 - front_weight) * exp(-front.a * front_weight);
  // Mean radiance of the two parts, each weighted by the optical depth the cone sees of it: a
  // convex mix of the two texels' own radiance, so no texel's light grows.
  float seen = front_weight * front.a + back_weight * back.a;
  c = 0.0;
  if (!(seen > 1e-8)) return vec4(0.0, 0.0, 0.0, tau);
  c = (front_weight * (forward ? ca : cb) + back_weight * (forward ? cb : ca)) * (tau / seen);
  return vec4((front_weight * front.rgb + back_weight * back.rgb) * (tau / seen), tau);
}

// The two layers of texels that straddle p along `axis` (texel coordinates t0, t1 as
// vct_fetch_layer takes them, t0 the lower) and the weight of t1, for vct_fetch_along.
float vct_along_layers(vec3 p, int level, int mip, int axis, out vec3 t0, out vec3 t1) {
  vec3 texel = vct_texel_coord(p, level, mip);
  float along = texel[axis] - 0.5;
  float first = floor(along);
  t0 = texel;
  t0[axis] = first + 0.5;
  t1 = texel;
  t1[axis] = first + 1.5;
  return along - first;
}

// A volume as a cone travelling along `axis` (0, 1, 2) sees it at p, in the form that adds
// along a ray (optical depth; contracts/vct_volume_encoding.glsl explains why): the two layers
// of texels that straddle p along the travel, each filtered across it in premultiplied
// opacity, then their optical depths interpolated along it. `forward`: the cone travels
// towards the axis's larger coordinates, so the lower layer is the one it meets first.
// The interpolation is the mean over one voxel length centred on p of texels that are
// constant over their own length: the cone crosses the front texel's part of that window,
// then the back texel's. The optical depth adds so; the radiance does not: the back part is
// seen through the front part, so its light counts through the front part's transmittance.
// (Interpolated alike, a sample past the middle of a wall's texel mixed in the dark texel
// behind the wall's face by up to half: cones that surfaces stop late, which the refinement in
// vct_sample_step makes them do, lost 2% of a closed box's light; docs/error-budget.md,
// twenty-seventh round.)
vec4 vct_fetch_along(sampler3D volume, vec3 p, int level, int mip, int axis, bool forward) {
  vec3 t0, t1;
  float w = vct_along_layers(p, level, mip, axis, t0, t1);
  vec4 a = vct_optical_depth(vct_fetch_layer(volume, t0, level, mip));
  if (!(w > 0.0)) return a;
  vec4 b = vct_optical_depth(vct_fetch_layer(volume, t1, level, mip));
  float unused;
  return vct_mix_along(a, b, 0.0, 0.0, w, forward, unused);
}

#if VCT_FRONT_LIGHT
// vct_fetch_along for the front-light mode: the light of `volume` and, in `share`, channel
// `axis` of its facing volume (the share of the opacity lying across the axis, premultiplied
// like the light), in the same optical-depth form and mixed alike.
vec4 vct_fetch_along_front(sampler3D volume, sampler3D facing, vec3 p, int level, int mip,
                           int axis, bool forward, out float share) {
  vec3 t0, t1;
  float w = vct_along_layers(p, level, mip, axis, t0, t1);
  vec4 la = vct_fetch_layer(volume, t0, level, mip);
  vec4 a = vct_optical_depth(la);
  float ca = vct_optical_depth(vec4(vct_fetch_layer(facing, t0, level, mip)[axis], 0.0, 0.0, la.a)).x;
  if (!(w > 0.0)) {
    share = ca;
    return a;
  }
  vec4 lb = vct_fetch_layer(volume, t1, level, mip);
  vec4 b = vct_optical_depth(lb);
  float cb = vct_optical_depth(vec4(vct_fetch_layer(facing, t1, level, mip)[axis], 0.0, 0.0, lb.a)).x;
  return vct_mix_along(a, b, ca, cb, w, forward, share);
}
#endif

#if VCT_FRONT_LIGHT
// One axis of the front-light read (vct_fetch_directional): the volume of dir's sign along
// `axis` (`positive` or `negative`) and its facing share, added to `light` and `shares` with
// weight |dir_k| and to the optical depth `tau` with weight dir_k^2. (The samplers come in as
// arguments so that every array index stays constant.)
void vct_add_axis_front(sampler3D positive, sampler3D negative, vec3 p, vec3 dir, int level,
                        int mip, int axis, inout vec3 light, inout float shares,
                        inout float tau) {
  float d = dir[axis];
  if (!(d * d > 0.0)) return;
  float share;
  vec4 v = d >= 0.0 ? vct_fetch_along_front(positive, vct_volumes[6], p, level, mip, axis, true,
                                            share)
                    : vct_fetch_along_front(negative, vct_volumes[7], p, level, mip, axis, false,
                                            share);
  tau += d * d * v.a;
  light += abs(d) * v.rgb;
  shares += abs(d) * share;
}
#endif

// A volume read by a cone travelling along dir: the volumes of its three axes weighted dir^2
// (they sum to 1, so a uniform medium is returned unchanged; docs/vct.md). Anisotropic: the
// axis's volume for the sign of dir along it; isotropic: the one volume along every axis.
//   Front light (VCT_FRONT_LIGHT): each axis's volume holds only the light of the surfaces facing
// its direction of travel, and its facing share the part of the opacity that lies across it;
// the cone reads the three axes' light over their shares, sum w_k light_k / sum w_k share_k,
// at the three axes' optical depth. A plane then shows its full radiance to every cone in
// front of it, whatever its tilt to the axes, and nothing to cones behind it; a voxel's dark
// surfaces across the axis take their part of what it shows.
vec4 vct_fetch_directional(vec3 p, vec3 dir, int level, int mip) {
  vec3 w = dir * dir;
  vec4 sum = vec4(0.0);
#if VCT_FRONT_LIGHT
  // The light and shares weighted |dir_k| (the projected area of a face across axis k), the
  // optical depth dir_k^2 as in the other modes.
  vec3 light = vec3(0.0);
  float shares = 0.0;
  vct_add_axis_front(vct_volumes[0], vct_volumes[1], p, dir, level, mip, 0, light, shares, sum.a);
  vct_add_axis_front(vct_volumes[2], vct_volumes[3], p, dir, level, mip, 1, light, shares, sum.a);
  vct_add_axis_front(vct_volumes[4], vct_volumes[5], p, dir, level, mip, 2, light, shares, sum.a);
  // Radiance light / shares, returned in the optical-depth form of sum.a.
  if (!(shares > 1e-8)) return vec4(0.0, 0.0, 0.0, sum.a);
  return vec4(light * (sum.a / (VCT_MAX_OPTICAL_DEPTH * shares)), sum.a);
#elif VCT_ANISOTROPIC
  if (w.x > 0.0) {
    sum += w.x * (dir.x >= 0.0 ? vct_fetch_along(vct_volumes[0], p, level, mip, 0, true)
                               : vct_fetch_along(vct_volumes[1], p, level, mip, 0, false));
  }
  if (w.y > 0.0) {
    sum += w.y * (dir.y >= 0.0 ? vct_fetch_along(vct_volumes[2], p, level, mip, 1, true)
                               : vct_fetch_along(vct_volumes[3], p, level, mip, 1, false));
  }
  if (w.z > 0.0) {
    sum += w.z * (dir.z >= 0.0 ? vct_fetch_along(vct_volumes[4], p, level, mip, 2, true)
                               : vct_fetch_along(vct_volumes[5], p, level, mip, 2, false));
  }
#else
  for (int k = 0; k < 3; ++k) {
    if (w[k] > 0.0) {
      sum += w[k] * vct_fetch_along(vct_volumes[0], p, level, mip, k, dir[k] >= 0.0);
    }
  }
#endif
  return sum;
}

#ifdef VCT_FACING_NORMALS
// How much of a voxel's light a cone travelling along dir receives: a surface sends light only
// to the side its normal faces; seen from behind it is as opaque and dark (the inside of a
// column, the unlit underside of a sunlit slab). n4 is the voxel normal texel interpolated like
// the volumes (contracts/voxel_volumes.glsl: xyz the mean of the writers' unit normals, w
// about 1 where occupied, so xyz / w is the occupied voxels' mean normal). The share of the
// voxel's footprint its front faces cover (voxel_front_share) follows from how far the
// writers agree: all of it or none for one plane, a part for a corner seen from behind one of
// its walls; all of it for a thin wall's two faces or a column, whose fronts hide their backs
// (which face's light shows, vct.filter's directional volumes already tell). This refines
// between the six axes, continuously in the cone's direction, what those volumes hold per
// axis. (A test only where |mean| >= 0.8 sent the full light of the voxels below, up to a
// third of Sponza's coarse ones, towards their backs: docs/error-budget.md, eighth round.)
float vct_facing(vec4 n4, vec3 dir) {
  if (!(n4.w > 0.05)) return 1.0;
  return voxel_front_share(n4.xyz / n4.w, -dir);
}
#endif

// Integer level of detail k (voxel edge = level-0 edge * 2^k): clipmap level k while there is
// one, then the mips of the coarsest level. `finest` is the finest level whose window holds p:
// only there does mip 0 hold the voxels' own light, which the facing test below is about.
// Coarser levels hold there the filter of finer voxels, into which vct.filter (given the
// faces) has already let each voxel's light only towards where its surfaces face; a mean
// normal of such a composite would dim it a second time (docs/error-budget.md, tenth round).
vec4 vct_fetch_lod(vec3 p, vec3 dir, int k, int finest) {
  int level = min(k, voxel_level_count() - 1);
  int mip = k - level;
  if (!voxel_level_valid(level)) return vec4(0.0);
  vec4 v = vct_fetch_directional(p, dir, level, mip);
#if defined(VCT_FACING_NORMALS) && !VCT_FRONT_LIGHT
  // (Front light needs no test: its volumes hold no light seen from behind.)
  // Only samples that carry light need the normals (most of a cone's samples are empty space).
  if (mip == 0 && level == finest && any(greaterThan(v.rgb, vec3(0.0)))) {
    v.rgb *= vct_facing(vct_fetch(VCT_FACING_NORMALS, p, level, 0), dir);
  }
#endif
  return v;
}

// The coarsest level of detail a point can use.
float vct_max_lod() {
  return float(voxel_level_count() - 1) + log2(float(voxel_resolution()));
}

// The coarsest mip of `level` whose trilinear footprint at p (2x2x2 texels) lies inside the
// level's window. Mip texels are aligned to the world grid, not to the toroidal window, so a
// texel that straddles the window's edge holds voxels from both of its opposite faces: a
// sample reaching it would see the far side of the volume (light through the open front of
// a box, from its back wall). Near the edges cones therefore sample finer mips.
int vct_window_mip_limit(vec3 p, int level) {
  int r = voxel_resolution();
#if VCT_UNWRAPPED_WINDOWS
  if (voxel_level_unwrapped(level)) return findMSB(r);  // nothing wraps: every mip in reach
#endif
  ivec3 origin = voxel_clipmap.levels[level].origin_voxel.xyz;
  vec3 window = voxel_window_coord(p, level);
  int top = findMSB(r);
  // The coarsest fitting mip, by a loop of constant trip count without an early exit, which
  // compilers unroll (llvmpipe's limit on loop iterations: voxel_finest_level).
  int mip = 0;
  for (int m = 1; m <= VCT_MAX_MIP; ++m) {
    float size = float(1 << m);
    vec3 remainder = vec3(origin - ((origin >> m) << m));
    // First texel of the footprint, in window voxels; the footprint is two texels wide.
    vec3 low = floor((window + remainder) / size - 0.5) * size - remainder;
    bool fits =
        all(greaterThanEqual(low, vec3(0.0))) && all(lessThanEqual(low + 2.0 * size, vec3(r)));
    if (m <= top && fits) mip = m;
  }
  return mip;
}

// The coarsest level of detail whose footprint at p stays inside the clipmap's windows.
float vct_window_lod_limit(vec3 p) {
  int coarsest = voxel_level_count() - 1;
  return float(coarsest + vct_window_mip_limit(p, coarsest));
}

// Filtered value (stored form, see above) at p for a cone travelling along dir, at a
// fractional level of detail (quadrilinear: trilinear in space, linear between lods). Levels
// finer than the finest one containing p are replaced by it; mips of the coarsest level are
// limited to those whose footprint stays inside its window. vec4(0) outside the volume.
vec4 vct_sample(vec3 p, vec3 dir, float lod) {
  int finest = voxel_finest_level(p, VCT_WINDOW_MARGIN);
  if (finest < 0) return vec4(0.0);
  lod = min(lod, vct_window_lod_limit(p));
  lod = clamp(lod, float(finest), vct_max_lod());
  int k = int(floor(lod));
  float f = lod - float(k);
  // Both levels through one call: each call site of a fetch is a whole copy of the directional
  // filter, and a driver that compiles the copies (lavapipe) takes seconds per pipeline.
  vec4 a = vec4(0.0);
  int fetches = f > 0.0 ? 2 : 1;
  for (int i = 0; i < fetches; ++i) {
    vec4 v = vct_fetch_lod(p, dir, k + i, finest);
    a = i == 0 ? v : mix(a, v, f);
  }
  return a;
}

// Finer voxels where a cone meets a surface: how many levels of detail finer a step is marched
// again where its sample holds a surface (vct_sample_step; 0: never; the passes' parameter
// "refine" sets it: 2 by default for the gathers, 1 for dvs's voxel bounces), and the opacity
// over the step that counts as holding one.
#ifndef VCT_REFINE_LEVELS
#define VCT_REFINE_LEVELS 1
#endif
#define VCT_REFINE_OPACITY 0.05

// The sample standing for the segment [p, p + dir * step] of a cone (`ratio` of its voxels at
// `lod`). A sample reaches about a voxel beyond its point on every side, so a surface blocks a
// cone from a voxel before the cone reaches it: a ceiling hid an emitter just under it from a
// wall below, and a block the light above its top edge from the floor in front of it, by as
// much as the cone's voxel, whatever the volume's resolution (docs/error-budget.md, fifteenth
// round). Where the sample is opaque enough to hold a surface, the segment is marched again at
// the whole level of detail VCT_REFINE_LEVELS finer (no finer than the finest level holding
// each point), front to back, and returned in the same form: the finer voxels say where the
// surface stops the cone, the cone's own voxels what it sends (its mean radiance over the
// cone's width: finer radiance would be a thin probe that hits or misses a small emitter).
// Whole levels, read without the facing test (opacity only), keep a refined step at one
// directional fetch per point: half the cost of interpolating between levels, for the same
// result (docs/error-budget.md, sixteenth round).
vec4 vct_sample_step(vec3 p, vec3 dir, float lod, float step, float ratio) {
  vec4 v = vct_sample(p, dir, lod);
  if (VCT_REFINE_LEVELS <= 0 || !(1.0 - exp(-max(v.a, 0.0) * ratio) > VCT_REFINE_OPACITY)) {
    return v;
  }
  int finest_at_p = max(voxel_finest_level(p, VCT_WINDOW_MARGIN), 0);
  int fine_k = max(int(round(lod)) - VCT_REFINE_LEVELS, finest_at_p);
  float levels = lod - float(fine_k);
  if (!(levels >= 0.5)) return v;  // the step is no coarser than its finest voxels
  int points = 1 << int(round(levels));
  float sub_step = step / float(points);
  float optical_depth = 0.0;  // of the whole step
  for (int k = 0; k < points; ++k) {
    vec3 q = p + dir * (float(k) * sub_step);
    // A point beyond the finest level at p reads the finest level that holds it.
    int finest = voxel_finest_level(q, VCT_WINDOW_MARGIN);
    if (finest < 0) continue;
    int kq = max(fine_k, finest);
    // Opacity only: no finest level passed, so no facing test.
    vec4 f = vct_fetch_lod(q, dir, kq, -1);
    optical_depth += max(f.a, 0.0) * sub_step / (voxel_size(0) * exp2(float(kq)));
  }
  float tau = optical_depth / max(ratio, 1e-6);  // per voxel length at lod
  vec3 mean = v.a > 1e-6 ? v.rgb / v.a : vec3(0.0);
  return vec4(mean * tau, tau);
}

struct VctCone {
  vec3 origin;     // anchor-relative
  vec3 direction;  // unit
  float tan_half_angle;
  // The surface the cone leaves (its tangent plane): unit normal, or vec3(0) for none, and the
  // origin's height above that plane in metres. Samples never reach below the plane.
  vec3 receiver_normal;
  float receiver_height;
  // A diffuse cone stands for a cell of the hemisphere (vct_diffuse_cone): where its lanes form
  // two rows, row 0 and row 1 lie at these heights over the receiver's plane (sin of their
  // elevation), in the lower and the upper half of the cell. Negative: the rows follow the
  // aperture (a specular or shadow cone, which stands for no cell).
  vec2 cell_rows;
};

// A cone from a point at `receiver_height` metres above a surface of unit normal n.
VctCone vct_cone_from_surface(vec3 origin, vec3 direction, float tan_half_angle, vec3 n,
                              float receiver_height) {
  VctCone cone;
  cone.origin = origin;
  cone.direction = direction;
  cone.tan_half_angle = tan_half_angle;
  cone.receiver_normal = n;
  cone.receiver_height = receiver_height;
  cone.cell_rows = vec2(-1.0);
  return cone;
}

// Where a diffuse cone's two rows of lanes lie (VctTraceSettings.lane_rows,
// vct_lane_directions): around the axis by its aperture, or in the halves of the cone's cell.
#define VCT_LANE_ROWS_APERTURE 0
#define VCT_LANE_ROWS_CELL 1

struct VctTraceSettings {
  float step_factor;     // beta: step length / cone diameter (0 < beta)
  int lanes;             // lanes of a capped cone, 1..VCT_MAX_LANES (vct_trace_cone)
  int lane_rows;         // VCT_LANE_ROWS_APERTURE or VCT_LANE_ROWS_CELL (diffuse cones)
  float max_distance;    // along the cone, scene units (FLT_MAX: no limit)
  float start_distance;  // skipped at the start, scene units (self-occlusion)
  float ao_falloff;      // lambda of f(r) = 1 / (1 + lambda r), r in level-0 voxel edges
};

struct VctConeResult {
  vec3 radiance;    // radiance arriving along the cone (W/sr/m^2)
  float opacity;    // accumulated opacity alpha (1 = fully blocked)
  float occlusion;  // ambient-occlusion term delta with the 1/(1+lambda r) falloff
};

// Front-to-back accumulation along one cone (seed 001 section 4, Crassin): at each step the
// sample's opacity over the step is 1 - exp(-tau * step / voxel edge), tau the interpolated
// optical depth of one voxel length, and its radiance the interpolated opacity-weighted mean, so
// that the result does not depend on beta. Stops when
// opaque, past max_distance or when the cone leaves the coarsest level.
//
// The receiver's own surface: a sample at height h above the receiver's tangent plane, taken at
// voxel edge D, mixes in every voxel whose centre is within D of it (trilinear), and the voxels
// holding the surface have their centres up to D/2 above the plane. With D > 2h/3 a cone would
// gather the surface it leaves (its radiance and its opacity), at every level of detail, since
// h and D both grow linearly along the cone: the self-illumination that made wide cones and
// fine volumes too bright (docs/vct.md, "Cones and the receiver's own surface"). So the level
// of detail is capped where the coarser of the two interpolated levels stays within 2h/3, and
// samples that even the finest available level cannot separate from the plane are lifted along
// the normal until it can.
// The step follows the voxel actually sampled, so a capped cone takes shorter steps instead of
// stepping over thin walls.
// What every step of a cone needs, worked out once per cone.
struct VctConeFrame {
  float tan_half;     // clamped aperture
  float base_size;    // level-0 voxel edge
  bool has_receiver;  // the cone leaves a surface
  float rise;         // height gained over the receiver per unit of t
  float lowest_rise;  // the same for the cone's lowest lane, whose height caps the level of detail
  float lod_bias;     // levels finer than the cone's diameter its samples are read at
};

VctConeFrame vct_cone_frame(VctCone cone) {
  VctConeFrame f;
  f.tan_half = clamp(cone.tan_half_angle, 1e-3, VCT_MAX_TAN_HALF_ANGLE);
  f.base_size = voxel_size(0);
  f.has_receiver = dot(cone.receiver_normal, cone.receiver_normal) > 0.25;
  f.rise = f.has_receiver ? dot(cone.direction, cone.receiver_normal) : 0.0;
  f.lowest_rise = f.rise;
  f.lod_bias = VCT_FOOTPRINT_LOD_BIAS;
  return f;
}

// Where a cone samples at distance t and how far that sample reaches (see vct_trace_cone).
struct VctConeStep {
  vec3 p;              // sample point, lifted off the receiver's plane where needed
  float diameter;      // the cone's width at t
  float lod;           // level of detail sampled
  float voxel;         // edge of the voxels sampled
  float coarse_voxel;  // edge of the coarser of the two levels interpolated
  float step_length;   // the segment [t, t + step_length] the sample stands for
};

// A sample point `height` above the receiver's plane, lifted where the step's coarser level
// cannot separate it from the plane (see vct_trace_cone).
vec3 vct_lift_off_receiver(VctCone cone, VctConeStep st, vec3 p, float height) {
  if (st.coarse_voxel <= (2.0 / 3.0) * height) return p;
  // Too close to the plane for the finest level present: sample straight above, where the
  // receiver's voxels no longer weigh in. Walls standing on the plane reach up there too,
  // so the cone still stops at them (skipping such samples let cones escape through them).
  return p + cone.receiver_normal * (1.5 * st.coarse_voxel - height);
}

// False once the cone's axis has left the volume. The step is filled in either way: the lanes
// beside the axis may still be inside (vct_trace_cone).
bool vct_cone_step(VctCone cone, VctConeFrame f, VctTraceSettings s, float t,
                   out VctConeStep st) {
  float base_size = f.base_size;
  bool has_receiver = f.has_receiver;
  st.p = cone.origin + t * cone.direction;
  int finest = voxel_finest_level(st.p, VCT_WINDOW_MARGIN);
  st.diameter = max(2.0 * t * f.tan_half, base_size);
  float lod = log2(st.diameter / base_size) - f.lod_bias;
  float height = cone.receiver_height + t * f.rise;
  // Capped for the lowest lane, the one nearest the receiver: the lanes share the level.
  float lowest = cone.receiver_height + t * f.lowest_rise;
  if (has_receiver) lod = min(lod, log2(max(lowest, 1e-6 * base_size) / (3.0 * base_size)));
  if (finest >= 0) lod = min(lod, vct_window_lod_limit(st.p));
  st.lod = clamp(lod, float(max(finest, 0)), vct_max_lod());
  st.voxel = base_size * exp2(st.lod);
  // Each sample stands for the segment [t, t + step]; the last one ends at max_distance.
  st.step_length = min(max(s.step_factor * st.voxel, 1e-2 * base_size), s.max_distance - t);
  st.coarse_voxel = base_size * exp2(ceil(st.lod));
  if (has_receiver) st.p = vct_lift_off_receiver(cone, st, st.p, height);
  return finest >= 0;
}

// Front-to-back compositing of one sample (stored form) over a step of `ratio` voxel lengths.
void vct_composite(vec4 v, float ratio, float falloff, inout vec3 radiance, inout float opacity,
                   inout float occlusion) {
  // Interpolated optical depth over the step, and the opacity-weighted mean radiance.
  float tau = max(v.a, 0.0);
  float corrected = 1.0 - exp(-tau * ratio);
  vec3 scaled = max(v.rgb, vec3(0.0)) * VCT_MAX_OPTICAL_DEPTH;  // radiance x tau
  vec3 colour = tau > 1e-6 ? scaled * (corrected / tau) : scaled * ratio;
  radiance += (1.0 - opacity) * colour;
  occlusion += (1.0 - occlusion) * corrected * falloff;
  opacity += (1.0 - opacity) * corrected;
}

// One lane: the cone's axis only. Kept apart from the lanes' loop, whose per-lane arrays cost
// 2.3x as much on lavapipe even with one lane.
VctConeResult vct_trace_cone_axis(VctCone cone, VctTraceSettings s) {
  VctConeResult result;
  result.radiance = vec3(0.0);
  result.opacity = 0.0;
  result.occlusion = 0.0;
  VctConeFrame frame = vct_cone_frame(cone);
  float base_size = frame.base_size;
  float t = max(s.start_distance, 0.0);
  for (int i = 0; i < VCT_MAX_STEPS; ++i) {
    if (result.opacity >= VCT_OPACITY_THRESHOLD || t >= s.max_distance) break;
    VctConeStep st;
    if (!vct_cone_step(cone, frame, s, t, st)) break;  // left the volume
    float ratio = st.step_length / st.voxel;
    vec4 v = vct_sample_step(st.p, cone.direction, st.lod, st.step_length, ratio);
    float falloff = 1.0 / (1.0 + s.ao_falloff * 0.5 * st.diameter / base_size);
    vct_composite(v, ratio, falloff, result.radiance, result.opacity, result.occlusion);
    t += st.step_length;
  }
  return result;
}

// The lanes' directions. A lane is the axis turned about the receiver's normal, so that it keeps
// its elevation: lanes offset along a straight tangent, axis + k side, leaned towards the horizon
// by up to atan(0.75 tan(half angle)), so the wider the cone, the more of its weight moved to low
// directions, which made the Cornell boxes 5 to 15 points darker (docs/error-budget.md, fifth
// round). With an even number of 6 or more, the lanes form two rows of lanes / 2, a quarter of
// the cone's half angle below and above the axis's elevation (the lower row kept above 3/4 of
// it); otherwise one row at the axis's elevation. Over the ring positions of an interleaved window
// those rows give the lowest 10 degrees of elevation 0.88 of their cosine-weighted share for 4, 9
// and 16 cones (and the next 10 degrees 0.90 for 4 and 9). With VCT_LANE_ROWS_CELL a diffuse cone's
// rows lie instead in the lower and the upper half of its ring (VctCone.cell_rows,
// vct_diffuse_cone), at the place the axis has in the whole ring, staggered by half a lane: its
// lanes then sample its cell in proportion to the cosine-weighted solid angle, so that the window's
// gather converges to the irradiance integral and each cone can be checked against its own band of
// the hemisphere (docs/error-budget.md, thirty-fifth round, says why that is not the default yet).
// In a row, lane k of n is turned by (2 (k + 1/2) / n - 1) times the cone's azimuthal half-width at
// the axis's elevation (k + 1/4 and k + 3/4 for a cell's rows). One row
// reads a capped cone at one elevation only: with 4 cones (up to 49 degrees of half angle) a
// surface whose grazing cones see lit walls at their axes' elevation and darkness just above
// read too bright, the more so the finer the voxels, and two rows of 4 lanes are what made
// every cone count fall with resolution (docs/error-budget.md, twenty-ninth round; two rows of 2
// lost the azimuths that narrow cones need). The lowest row caps the level of detail of all
// (vct_cone_step): each lane capped for its own height let the upper ones read coarser voxels,
// whose light reached further beside an emitter's edge.
void vct_lane_directions(VctCone cone, inout VctConeFrame frame, int lanes,
                         out vec3 directions[VCT_MAX_LANES]) {
  float rise = frame.rise;
  vec3 along = cone.direction - cone.receiver_normal * rise;  // horizontal part
  float horizontal = length(along);
  vec3 heading = along / max(horizontal, 1e-6);
  vec3 side = cross(cone.direction, cone.receiver_normal);
  float side_len = length(side);
  side = side_len > 1e-6 ? side / side_len : vec3(0.0);
  // Directions at elevation angle theta inside a cone of half angle h around the axis span the
  // azimuths |phi| <= phi_max, cos h = cos^2 theta + sin^2 theta cos phi_max.
  float cos_half = inversesqrt(1.0 + frame.tan_half * frame.tan_half);
  float cos_phi_max = (cos_half - rise * rise) / max(horizontal * horizontal, 1e-6);
  float phi_max = acos(clamp(cos_phi_max, -1.0, 1.0));
  float elevation = asin(clamp(rise, -1.0, 1.0));
  int rows = lanes >= 6 && lanes % 2 == 0 ? 2 : 1;
  int per_row = lanes / rows;
  float quarter = rows == 2 ? 0.25 * atan(frame.tan_half) : 0.0;
  for (int j = 0; j < lanes; ++j) {
    int k = j / rows;
    float slot = float(k) + 0.5;
    float e = elevation;
    if (rows == 2 && cone.cell_rows.x >= 0.0) {
      // A cell's rows, staggered by half a lane in azimuth.
      e = asin(clamp(cone.cell_rows[j % 2], 0.0, 1.0));
      slot += j % 2 == 0 ? -0.25 : 0.25;
    } else if (rows == 2) {
      e = j % 2 == 0 ? max(elevation - quarter, 0.75 * elevation)
                     : min(elevation + quarter, 0.5 * VCT_PI);
    }
    float phi = (2.0 * slot / float(per_row) - 1.0) * phi_max;
    directions[j] = (heading * cos(phi) + side * sin(phi)) * cos(e) + cone.receiver_normal * sin(e);
    frame.lowest_rise = min(frame.lowest_rise, sin(e));
  }
}

VctConeResult vct_trace_cone(VctCone cone, VctTraceSettings s) {
  int lanes = clamp(s.lanes, 1, VCT_MAX_LANES);
  VctConeFrame frame = vct_cone_frame(cone);
  bool can_spread = frame.has_receiver && abs(frame.rise) < 1.0 - 1e-5;
  if (lanes == 1 || !can_spread) return vct_trace_cone_axis(cone, s);
  float base_size = frame.base_size;
  vec3 lane_direction[VCT_MAX_LANES];
  vct_lane_directions(cone, frame, lanes, lane_direction);
  // Each lane stands for 1 / lanes of the cross-section: a disc sqrt(lanes) times narrower.
  frame.lod_bias += 0.5 * log2(float(lanes));
  // The cone's lanes (see below): radiance, opacity and occlusion of each.
  vec3 lane_radiance[VCT_MAX_LANES];
  float lane_opacity[VCT_MAX_LANES];
  float lane_occlusion[VCT_MAX_LANES];
  for (int j = 0; j < VCT_MAX_LANES; ++j) {
    lane_radiance[j] = vec3(0.0);
    lane_opacity[j] = 0.0;
    lane_occlusion[j] = 0.0;
  }
  float t = max(s.start_distance, 0.0);
  for (int i = 0; i < VCT_MAX_STEPS; ++i) {
    if (t >= s.max_distance) break;
    VctConeStep st;
    bool axis_inside = vct_cone_step(cone, frame, s, t, st);
    // A cone's voxels are narrower than the cone (capped near the receiver, and a level finer
    // than its diameter everywhere, VCT_FOOTPRINT_LOD_BIAS): one sample on its axis would be a
    // thin probe carrying the whole cone's weight, which hits or misses a small bright
    // surface (an area light) and paints it as blotches that move with the cone layout. So
    // the cone is a fan of `lanes` thin lanes spread across its width (vct_lane_directions),
    // each composited on its own, so that a lane stops at the wall it meets and the lanes
    // beside it go on. Where the voxels are as wide as the cone (the coarsest level) the lanes
    // coincide and share the axis's sample. Each lane ends where it leaves the volume, not
    // where the axis does (lanes that met their wall after the axis had left were cut short).
    bool spread = st.diameter > 1.5 * st.voxel;
    if (!spread && !axis_inside) break;
    float ratio = st.step_length / st.voxel;
    float falloff = 1.0 / (1.0 + s.ao_falloff * 0.5 * st.diameter / base_size);
    // Unspread, the lanes share the axis's sample, taken by the first lane that needs it (one
    // call site of vct_sample_step: see vct_sample).
    vec4 v = vec4(0.0);
    bool sampled = false;
    bool any_inside = !spread;
    // The most transparent lane after this step, found in the lanes' own loop: a loop of its
    // own would add to llvmpipe's count of loop iterations (voxel_finest_level).
    float open = 0.0;
    for (int j = 0; j < lanes; ++j) {
      if (lane_opacity[j] >= VCT_OPACITY_THRESHOLD) continue;
      vec3 q = st.p;
      vec3 d = cone.direction;
      bool inside = true;
      if (spread) {
        // The shared level of detail, each lane lifted for its own height over the receiver.
        d = lane_direction[j];
        float height = cone.receiver_height + t * dot(d, cone.receiver_normal);
        q = vct_lift_off_receiver(cone, st, cone.origin + t * d, height);
        inside = voxel_finest_level(q, VCT_WINDOW_MARGIN) >= 0;
        any_inside = any_inside || inside;
      }
      if (inside) {
        if (spread || !sampled) v = vct_sample_step(q, d, st.lod, st.step_length, ratio);
        sampled = true;
        vct_composite(v, ratio, falloff, lane_radiance[j], lane_opacity[j], lane_occlusion[j]);
      }
      open = max(open, 1.0 - lane_opacity[j]);
    }
    if (!any_inside || open <= 1.0 - VCT_OPACITY_THRESHOLD) break;
    t += st.step_length;
  }
  VctConeResult result;
  result.radiance = vec3(0.0);
  result.opacity = 0.0;
  result.occlusion = 0.0;
  for (int j = 0; j < lanes; ++j) {
    result.radiance += lane_radiance[j] / float(lanes);
    result.opacity += lane_opacity[j] / float(lanes);
    result.occlusion += lane_occlusion[j] / float(lanes);
  }
  return result;
}

// An orthonormal tangent frame around a unit normal (no singularity at any normal).
void vct_tangent_frame(vec3 n, out vec3 t, out vec3 b) {
  float sign_z = n.z >= 0.0 ? 1.0 : -1.0;
  float a = -1.0 / (sign_z + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0 + sign_z * n.x * n.x * a, sign_z * c, -sign_z * n.x);
  b = vec3(c, sign_z + n.y * n.y * a, -n.y);
}

#define VCT_MAX_DIFFUSE_CONES 32

// The i-th of `count` diffuse cones (1..VCT_MAX_DIFFUSE_CONES) in tangent space (z = normal).
// Cosine-weighted solid angle is area on the unit disk the hemisphere projects to (disk radius
// sin theta, dA = cos theta d omega), so `count` points spread evenly over that disk are a
// quadrature of the irradiance integral with equal weights pi/count; they sum to exactly pi,
// and a uniform environment of radiance L gives irradiance pi*L for every count. The points
// are a golden-angle (Vogel) spiral: point i in the ring radius^2 in [i, i + 1)/count, at
// radius^2 (i + ring_position)/count, so every count covers both the polar angle and the
// azimuth evenly, down to near the horizon. (Cones at the
// cosine-weighted centroids of one ring of sectors all sat at one polar angle, about 48
// degrees, so adding cones never refined theta, and cones that lie low over their receiver
// are narrowed to near-rays; see vct_trace_cone.) Each cone's aperture is the solid angle
// of its share of the disk, pi/count / cos theta. `rotation` (radians) turns the whole set
// about the normal and `ring_position` (0..1, 0.5 = the ring's middle) moves every cone within
// its ring: a few cones in one fixed set see a scene from a few arbitrary directions, and the
// same ones on every point of a plane, so callers vary both between neighbouring points and
// let their gathers average (docs/vct.md, "Interleaved cone sets").
// sin^2 of the polar angle at `ring_position` (0..1) of diffuse cone `index`'s ring (below).
float vct_ring_sin2(int index, int count, float ring_position) {
  return count == 1 ? 0.0 : min((float(index) + ring_position) / float(count), 1.0 - 1e-4);
}

void vct_diffuse_cone(int index, int count, float rotation, float ring_position,
                      out vec3 direction, out float weight, out float tan_half_angle,
                      out vec2 cell_rows) {
  count = clamp(count, 1, VCT_MAX_DIFFUSE_CONES);
  index = clamp(index, 0, count - 1);
  weight = VCT_PI / float(count);
  const float golden_angle = 2.39996323;  // pi (3 - sqrt 5)
  float ring = clamp(ring_position, 0.0, 1.0);
  float sin2 = vct_ring_sin2(index, count, ring);
  // The lanes' two rows at the same place in the lower and the upper half of the ring.
  cell_rows = sqrt(vec2(1.0 - vct_ring_sin2(index, count, 0.5 + 0.5 * ring),
                        1.0 - vct_ring_sin2(index, count, 0.5 * ring)));
  float sin_theta = sqrt(sin2);
  float cos_theta = sqrt(1.0 - sin2);
  float phi = float(index) * golden_angle + rotation;
  direction = vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
  float solid_angle = min(weight / cos_theta, 2.0 * VCT_PI);
  // A cone of half angle h has solid angle 2 pi (1 - cos h).
  float cos_half = clamp(1.0 - solid_angle / (2.0 * VCT_PI), 0.0, 1.0);
  float sin_half = sqrt(max(1.0 - cos_half * cos_half, 0.0));
  tan_half_angle = min(sin_half / max(cos_half, 1e-4), VCT_MAX_TAN_HALF_ANGLE);
}

// Irradiance E (W/m^2) at anchor-relative p, a point of a surface with unit normal n, from
// `count` diffuse cones turned by `rotation` about n and placed at `ring_position` in their
// rings (vct_diffuse_cone), and the ambient-occlusion visibility (1 = open) in `visibility`.
// The cones start `normal_offset` (metres) off the surface. Outgoing diffuse radiance is
// c_diff / pi * E. With `trace_extra`, one more cone, `extra` with `extra_max_distance`, goes
// through the same loop first and its opacity comes back in `extra_opacity` (a soft-shadow
// cone): every call site of vct_trace_cone is a whole copy of the tracer in the pipeline, and a
// driver that compiles the copies (lavapipe) takes seconds per pipeline.
vec3 vct_diffuse_irradiance_and_cone(vec3 p, vec3 n, int count, float rotation,
                                     float ring_position, float normal_offset,
                                     VctTraceSettings s, bool trace_extra, VctCone extra,
                                     float extra_max_distance, out float visibility,
                                     out float extra_opacity) {
  vec3 t, b;
  vct_tangent_frame(n, t, b);
  vec3 origin = p + n * normal_offset;
  vec3 irradiance = vec3(0.0);
  float occlusion = 0.0;
  extra_opacity = 0.0;
  count = clamp(count, 1, VCT_MAX_DIFFUSE_CONES);
  for (int i = trace_extra ? -1 : 0; i < count; ++i) {
    VctCone cone = extra;
    VctTraceSettings cone_settings = s;
    float weight = 0.0;
    if (i >= 0) {
      vec3 d;
      float tan_half;
      vec2 cell_rows;
      vct_diffuse_cone(i, count, rotation, ring_position, d, weight, tan_half, cell_rows);
      cone = vct_cone_from_surface(origin, normalize(t * d.x + b * d.y + n * d.z), tan_half, n,
                                   normal_offset);
      if (s.lane_rows == VCT_LANE_ROWS_CELL) cone.cell_rows = cell_rows;
    } else {
      cone_settings.max_distance = extra_max_distance;
    }
    VctConeResult r = vct_trace_cone(cone, cone_settings);
    if (i < 0) {
      extra_opacity = r.opacity;
      continue;
    }
    irradiance += weight * r.radiance;
    occlusion += weight * r.occlusion;
  }
  visibility = clamp(1.0 - occlusion / VCT_PI, 0.0, 1.0);
  return irradiance;
}

vec3 vct_diffuse_irradiance(vec3 p, vec3 n, int count, float rotation, float ring_position,
                            float normal_offset, VctTraceSettings s, out float visibility) {
  float unused;
  return vct_diffuse_irradiance_and_cone(p, n, count, rotation, ring_position, normal_offset, s,
                                         false, vct_cone_from_surface(p, n, 0.0, n, 0.0), 0.0,
                                         visibility, unused);
}

// Specular cone aperture for a GGX perceptual roughness (alpha = roughness^2). The GGX
// distribution falls to half its peak at tan(theta_h) = alpha * sqrt(sqrt(2) - 1); reflection
// doubles angles, so the reflected lobe's half-maximum half angle is 2 * atan(0.6436 alpha).
// Clamped to [0.5 degrees, 60 degrees].
float vct_specular_tan_half_angle(float roughness) {
  float alpha = clamp(roughness, 0.0, 1.0);
  alpha *= alpha;
  float half_angle = clamp(2.0 * atan(0.6435943 * alpha), 0.0087266, 1.0471976);
  return tan(half_angle);
}

#endif
