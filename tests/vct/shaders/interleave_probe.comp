#version 460
#extension GL_GOOGLE_include_directive : require
// Test probe of vct/interleave_layout.glsl: the cone set (i, j) of every pixel of a 2n x 2n
// block, row by row, for the window size n in the push constant.
#include "vct/interleave_layout.glsl"

layout(local_size_x = 1) in;

layout(set = 0, binding = 0, std430) readonly buffer Unused { int unused[]; };
layout(set = 0, binding = 1, std430) writeonly buffer Cells { ivec2 cells[]; };

layout(push_constant) uniform Push { uint n; } pc;

void main() {
  int n = int(pc.n);
  for (int y = 0; y < 2 * n; ++y) {
    for (int x = 0; x < 2 * n; ++x) cells[y * 2 * n + x] = vct_interleave_cell(ivec2(x, y), n);
  }
}
