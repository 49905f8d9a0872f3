#ifndef VOXGI_LPV_CELLS_GLSL
#define VOXGI_LPV_CELLS_GLSL
// Cells of the LPV (C++ twin: passes/lpv/lpv_layout.hpp): one per voxel of each level of the
// voxel clipmap, in window order (not toroidal: the LPV is rebuilt whenever a window moves).
// Its volumes ("cascades") are, for a clipmap of L levels, first the L levels holding the light
// of every light source inside their window ("all"), then the levels 1 .. L-1 again holding
// only the light of the sources inside their window but outside the next finer one ("outer"):
// a pixel whose finest level is f adds f's "all" to the "outer" volumes of the levels above,
// so that every source is counted once, by the finest level that holds it (lpv/lookup.comp).
//   cell = ((cascade * R + z) * R + y) * R + x,
// then the octree levels o = 1, 2, ... (seed 002 sec. 4.2) of (R >> o)^3 cells per cascade,
// each counted the same way from the end of the level before.
// Include after contracts/voxel_clipmap.glsl.

// The LPV's volumes: 2 L - 1 for a clipmap of L levels.
int lpv_cascade_count() { return 2 * voxel_level_count() - 1; }
// The clipmap level of a volume.
int lpv_cascade_level(int cascade) {
  int levels = voxel_level_count();
  return cascade < levels ? cascade : cascade - levels + 1;
}
// The volume of level `level` (>= 1) that holds only the light of sources outside the window of
// level - 1.
int lpv_outer_cascade(int level) { return voxel_level_count() + level - 1; }

// vec4s per cell record (lpv.downsample's injected levels, lpv.propagate's accumulated levels,
// lpv.merge's radiance): SH intensity r, g, b; the flux the cell's geometry stopped (rgb) and
// its index mark (w: the cell's octree level where light is in it, -1 where none; after the
// merge, the level the cell took); the cell's geometry (xyz mean normal, w opacity).
const int LPV_RECORD_VEC4S = 5;

int lpv_cell(ivec3 c, int cascade) {
  int r = voxel_resolution();
  return ((cascade * r + c.z) * r + c.y) * r + c.x;
}

bool lpv_inside(ivec3 c) {
  return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(voxel_resolution())));
}

// The voxels of every clipmap level.
int lpv_voxel_total() {
  int r = voxel_resolution();
  return r * r * r * voxel_level_count();
}

// Octree levels: level o has (R >> o)^3 cells per cascade; level 0 is lpv_cell's.
int lpv_level_resolution(int o) { return voxel_resolution() >> o; }

int lpv_level_base(int o) {
  int base = 0;
  for (int i = 0; i < o; ++i) {
    int n = lpv_level_resolution(i);
    base += n * n * n * lpv_cascade_count();
  }
  return base;
}

// The cell c of a cascade on a level of n cells per side whose first cell is `base`.
int lpv_octree_cell_at(int base, int n, ivec3 c, int cascade) {
  return base + ((cascade * n + c.z) * n + c.y) * n + c.x;
}

int lpv_octree_cell(ivec3 c, int cascade, int o) {
  return lpv_octree_cell_at(lpv_level_base(o), lpv_level_resolution(o), c, cascade);
}

bool lpv_octree_inside(ivec3 c, int o) {
  return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(lpv_level_resolution(o))));
}

// The cell (xyz), cascade and octree level of an index over the cells of `levels` levels;
// level = levels where the index is past them.
struct LpvOctreeCell {
  ivec3 c;
  int cascade;
  int level;
};

LpvOctreeCell lpv_octree_coords(int index, int levels) {
  LpvOctreeCell cell;
  cell.level = levels;
  int base = 0;
  for (int o = 0; o < levels; ++o) {
    int n = lpv_level_resolution(o);
    int count = n * n * n * lpv_cascade_count();
    if (index < base + count) {
      int i = index - base;
      cell.c = ivec3(i % n, (i / n) % n, (i / (n * n)) % n);
      cell.cascade = i / (n * n * n);
      cell.level = o;
      return cell;
    }
    base += count;
  }
  return cell;
}

// Fixed-point injection (seed 002's float atomics are order-dependent): every contribution is
// rounded to an integer multiple of 1 / scale and added with integer atomics, so the sums are
// the same whatever order threads run in. With at most `contributions` values of magnitude at
// most `max_magnitude` adding up in one coefficient, scale = 2^30 / (contributions x
// max_magnitude) keeps every sum below 2^30 in magnitude: no overflow is possible.
float lpv_fixed_point_scale(uint max_magnitude_bits, uint contributions) {
  float m = uintBitsToFloat(max_magnitude_bits);
  if (!(m > 0.0) || isinf(m) || contributions == 0u) return 0.0;
  return 1073741824.0 / (float(contributions) * m);
}

#endif
