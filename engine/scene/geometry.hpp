#pragma once
// Vertex-data repair shared by the glTF loader and SceneBuilder. Everything here keeps its
// output finite whatever the input (degenerate triangles, zero normals, collinear UVs).

#include <cstdint>
#include <vector>

#include "engine/scene/scene.hpp"

namespace voxgi::scene {

// Unit vector perpendicular to the unit vector n.
glm::vec3 any_perpendicular(const glm::vec3& n);

// Gives every triangle its own three vertices and the triangle's face normal (for primitives
// without normals). Degenerate triangles get +Y.
void make_flat_normals(Primitive& primitive);

// Normalizes normals; zero-length or non-finite ones get the area-weighted normal of the
// triangles around the vertex, and +Y when those are degenerate too.
void repair_normals(Primitive& primitive);

// Per-vertex tangents from per-triangle UV derivatives, accumulated per vertex, then
// Gram-Schmidt against the normal; w = handedness (±1). Vertices whose UVs are degenerate get
// an arbitrary tangent orthonormal to the normal.
void generate_tangents(Primitive& primitive);

// Keeps valid supplied tangents (re-orthonormalized against the normal, w forced to ±1) and
// regenerates all of them when any is zero-length or non-finite.
void repair_tangents(Primitive& primitive);

void compute_bounds(Primitive& primitive);

// The same triangles with the opposite winding (two indices swapped per triangle).
std::vector<uint32_t> flip_winding(const std::vector<uint32_t>& indices);

}  // namespace voxgi::scene
