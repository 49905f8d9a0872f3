#ifndef VOXGI_VOXEL_CLIPMAP_GLSL
#define VOXGI_VOXEL_CLIPMAP_GLSL
// Contract: the voxel clipmap description and addressing shared by every voxel family
// (voxelization, light injection, filtering, cone tracing, deferred voxel shading). C++ twin of
// the VoxelClipmapInfo buffer: passes/contracts/voxel_clipmap.hpp (std430, 288 bytes).
//
// A clipmap resource is one 3D image of extent (R, R, R * L): level l occupies texels
// z in [l * R, (l + 1) * R). Level 0 is the finest. Level l has voxels of edge
// voxel_size(l) = level0 size * 2^l and covers the world box [level_min(l), level_min(l) + R *
// voxel_size(l)). Storage is toroidal: the voxel with integer index v (per level, counted from
// the anchor) lives at texel (v mod R) + (0, 0, l * R), so moving the window only invalidates
// the slabs that entered it. Window corners are an even number of their voxels from the anchor,
// so every level's window lies on the grid of the next coarser level (levels are nested). A
// single level fitted to the scene (L = 1) is the dense volume of the source documents.
// Windows that stay put start at a multiple of R (passes/common/voxel_clipmap_window.hpp,
// fixed_window_anchor): their storage is the identity and their faces are the texture's.
//
// World positions are made relative to `anchor` before any voxel arithmetic so that scenes far
// from the origin keep float precision (the CPU computes anchor-relative corners in double).
//
// Include after defining VOXEL_CLIPMAP_SET and VOXEL_CLIPMAP_BINDING (defaults: set 0,
// binding 0). The buffer is the graph resource written by the voxelization pass.

#ifndef VOXEL_CLIPMAP_SET
#define VOXEL_CLIPMAP_SET 0
#endif
#ifndef VOXEL_CLIPMAP_BINDING
#define VOXEL_CLIPMAP_BINDING 0
#endif

#define VOXEL_CLIPMAP_MAX_LEVELS 8
// Levels a shader may meet (contracts::clipmap_levels_define): the bound of voxel_finest_level.
#ifndef VOXEL_CLIPMAP_LEVELS
#define VOXEL_CLIPMAP_LEVELS VOXEL_CLIPMAP_MAX_LEVELS
#endif

struct VoxelClipmapLevel {
  // xyz: voxel index (in voxels of this level) of the window's min corner, counted from the
  // anchor, which lies on every level's grid; w: 1 once valid
  ivec4 origin_voxel;
  vec4 min_corner_size;   // xyz: window min corner relative to anchor (m); w: voxel edge (m)
};

layout(std430, set = VOXEL_CLIPMAP_SET, binding = VOXEL_CLIPMAP_BINDING) readonly buffer
VoxelClipmapInfo {
  vec4 anchor;            // xyz: world-space anchor (m); w: unused
  uvec4 dims;             // x: R (voxels per level edge), y: L (levels), z, w: unused
  VoxelClipmapLevel levels[VOXEL_CLIPMAP_MAX_LEVELS];
} voxel_clipmap;

int voxel_resolution() { return int(voxel_clipmap.dims.x); }
int voxel_level_count() { return int(voxel_clipmap.dims.y); }
float voxel_size(int level) { return voxel_clipmap.levels[level].min_corner_size.w; }
vec3 voxel_level_min(int level) { return voxel_clipmap.levels[level].min_corner_size.xyz; }
bool voxel_level_valid(int level) { return voxel_clipmap.levels[level].origin_voxel.w != 0; }

// Anchor-relative position from a world-space one.
vec3 voxel_relative(vec3 world) { return world - voxel_clipmap.anchor.xyz; }

// Continuous coordinate inside level `level`'s window, in voxels: [0, R) inside.
vec3 voxel_window_coord(vec3 relative_position, int level) {
  return (relative_position - voxel_level_min(level)) / voxel_size(level);
}

bool voxel_inside_window(vec3 window_coord) {
  return all(greaterThanEqual(window_coord, vec3(0.0))) &&
         all(lessThan(window_coord, vec3(float(voxel_resolution()))));
}

// Whether level `level` starts at a multiple of R: stored without the wrap, every mip's window
// starting at texel 0.
bool voxel_level_unwrapped(int level) {
  ivec3 origin = voxel_clipmap.levels[level].origin_voxel.xyz;
  return all(equal(origin & (voxel_resolution() - 1), ivec3(0)));
}

// Texel of the voxel at integer window coordinate `window_voxel` (0..R-1) of `level`, applying
// the toroidal wrap.
ivec3 voxel_texel(ivec3 window_voxel, int level) {
  int r = voxel_resolution();
  ivec3 world_voxel = window_voxel + voxel_clipmap.levels[level].origin_voxel.xyz;
  ivec3 wrapped = ((world_voxel % r) + r) % r;
  return ivec3(wrapped.xy, wrapped.z + level * r);
}

// The finest level whose window contains `relative_position` with `margin` voxels to spare,
// or -1 when none does. A constant trip count and no early exit, so that compilers unroll it:
// llvmpipe ends every loop of an invocation once all its loops together have run 65535
// iterations, and this search, run for every sample of every cone, counted towards that
// (docs/error-budget.md, twenty-third round).
int voxel_finest_level(vec3 relative_position, float margin) {
  float r = float(voxel_resolution());
  int count = voxel_level_count();
  int finest = -1;
  for (int level = min(VOXEL_CLIPMAP_LEVELS, VOXEL_CLIPMAP_MAX_LEVELS) - 1; level >= 0; --level) {
    vec3 c = voxel_window_coord(relative_position, level);
    bool inside = all(greaterThanEqual(c, vec3(margin))) && all(lessThan(c, vec3(r - margin)));
    if (level < count && inside) finest = level;
  }
  return finest;
}

#endif
