#ifndef VOXGI_LPV_CELLS_GLSL
#define VOXGI_LPV_CELLS_GLSL
// Cells of the LPV (C++ twin: passes/lpv/lpv_layout.hpp): one per voxel of each level of the
// voxel clipmap, in window order (not toroidal: the LPV is rebuilt whenever a window moves),
//   cell = ((level * R + z) * R + y) * R + x.
// Include after contracts/voxel_clipmap.glsl.

// vec4s per cell in lpv.propagate's radiance buffer: SH intensity r, g, b; the flux the cell's
// geometry stopped (rgb); the cell's geometry (xyz mean normal, w opacity).
const int LPV_RADIANCE_VEC4S = 5;

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
