#ifndef VOXGI_VOXEL_DRAW_GLSL
#define VOXGI_VOXEL_DRAW_GLSL
// Push constants of the voxelization draw (vertex, geometry and fragment stages). Mirrors
// VoxelDrawPush in passes/common/voxelize_pass.cpp.
//
// Coordinates: "window" coordinates are voxels of the level being voxelized, 0..R along each
// axis of the level's window. A draw fills one box of that window; the viewport is
// box_min.w x box_min.w pixels and pixel (0, 0) is the box's min corner on the two axes of the
// triangle's projection plane. "Anchored" coordinates are voxels of the level from the
// anchor: window + origin, but computed without the window, so that they are the same floats
// whichever window a triangle is voxelized in (decisions that compare them with thresholds,
// like the front-surface keys, then come out the same after the window scrolls).

layout(push_constant) uniform VoxelDrawPush {
  vec4 anchor;          // xyz: world anchor (m)
  vec4 level_min_size;  // xyz: window min corner relative to the anchor (m); w: voxel edge (m)
  ivec4 box_min;        // xyz: box min (window voxels); w: viewport edge in pixels
  ivec4 box_max;        // xyz: box max, exclusive; w: scratch words per voxel
  ivec4 origin;         // xyz: the window's min corner in voxels from the anchor
} voxel_draw;

#endif
