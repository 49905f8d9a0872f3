#ifndef VOXGI_LPV_CELLS_GLSL
#define VOXGI_LPV_CELLS_GLSL
// Cells of the LPV (C++ twin: passes/lpv/lpv_layout.hpp): one per voxel of each level of the
// voxel clipmap (a cascade), in window order (not toroidal: the LPV is rebuilt whenever a
// window moves),
//   cell = ((cascade * R + z) * R + y) * R + x,
// then the octree levels o = 1, 2, ... (seed 002 sec. 4.2) of (R >> o)^3 cells per cascade,
// each counted the same way from the end of the level before.
// Include after contracts/voxel_clipmap.glsl.

// vec4s per cell record (lpv.downsample's injected levels, lpv.propagate's accumulated levels,
// lpv.merge's radiance): SH intensity r, g, b; the flux the cell's geometry stopped (rgb) and
// its index mark (w: the cell's octree level where light is in it, -1 where none; after the
// merge, the level the cell took); the cell's geometry (xyz mean normal, w opacity).
const int LPV_RECORD_VEC4S = 5;

int lpv_cell(ivec3 c, int level) {
  int r = voxel_resolution();
  return ((level * r + c.z) * r + c.y) * r + c.x;
}

bool lpv_inside(ivec3 c) { return all(greaterThanEqual(c, ivec3(0))) && all(lessThan(c, ivec3(voxel_resolution()))); }

// The cell and level of a linear invocation index over all cells.
ivec4 lpv_cell_coords(uint index) {
  int r = voxel_resolution();
  int i = int(index);
  return ivec4(i % r, (i / r) % r, (i / (r * r)) % r, i / (r * r * r));
}

int lpv_cell_total() {
  int r = voxel_resolution();
  return r * r * r * voxel_level_count();
}

// Octree levels: level o has (R >> o)^3 cells per cascade; level 0 is lpv_cell's.
int lpv_level_resolution(int o) { return voxel_resolution() >> o; }

int lpv_level_base(int o) {
  int base = 0;
  for (int i = 0; i < o; ++i) {
    int n = lpv_level_resolution(i);
    base += n * n * n * voxel_level_count();
  }
  return base;
}

int lpv_octree_cell(ivec3 c, int cascade, int o) {
  int n = lpv_level_resolution(o);
  return lpv_level_base(o) + ((cascade * n + c.z) * n + c.y) * n + c.x;
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
    int count = n * n * n * voxel_level_count();
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
