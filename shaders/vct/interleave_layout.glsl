#ifndef VOXGI_VCT_INTERLEAVE_LAYOUT_GLSL
#define VOXGI_VCT_INTERLEAVE_LAYOUT_GLSL
// Which of the n x n interleaved cone sets a pixel traces (vct.cone_trace, docs/vct.md,
// "Interleaved cone sets"): (i, j), each in [0, n^2), the set turned by 2 pi i / n^2 about the
// normal with every cone at (j + 1/2) / n^2 of its ring. i = n a + b and j = n b + a for a(x, y),
// b(x, y) two orthogonal Latin squares of order n, so that every n x n window holds each turn
// and each ring position once, the n^2 pairs fill the (turn, ring) square one per n x n block
// of it, and every row and column of the window (all that a surface one or two pixels wide
// averages) holds one turn from each n-th of the circle and one position from each n-th of the
// ring. With i = (x mod n) n + (y mod n), j = (y mod n) n + (x mod n) a column of pixels held a
// quarter of the circle and a row a quarter of the ring (docs/error-budget.md, thirty-third
// round). Order 2 has no orthogonal pair and keeps that layout. Checked by
// tests/vct/interleave_layout_test.cpp.

// Order 4: one of each symbol in every aligned 2 x 2 block too, indexed (y mod 4) * 4 + x mod 4.
const int kVctInterleaveLatinA[16] = int[16](0, 1, 2, 3, 2, 3, 0, 1, 1, 0, 3, 2, 3, 2, 1, 0);
const int kVctInterleaveLatinB[16] = int[16](0, 1, 2, 3, 3, 2, 1, 0, 2, 3, 0, 1, 1, 0, 3, 2);

ivec2 vct_interleave_cell(ivec2 pixel, int n) {
  n = max(n, 1);
  int x = pixel.x % n;
  int y = pixel.y % n;
  int a = x;
  int b = y;
  if (n == 4) {
    a = kVctInterleaveLatinA[y * 4 + x];
    b = kVctInterleaveLatinB[y * 4 + x];
  } else if (n % 2 == 1) {
    a = (x + y) % n;  // orthogonal Latin squares for every odd n
    b = (x + 2 * y) % n;
  }
  return ivec2(n * a + b, n * b + a);
}

#endif
