#pragma once
// Scenes for the hard cases of HARD-CASES.md, built in code, that the foundation, vct and dvs
// hard-case tests share. Builders that take a `surface` material use it for every surface;
// by default that is matte(0.8).

#include <glm/glm.hpp>

#include <string>

#include "engine/scene/scene.hpp"
#include "engine/scene/scene_builder.hpp"

namespace voxgi::test {

// Base colour `albedo`, metallic 0, roughness 1, emitting `emissive`.
scene::Material matte(glm::vec3 albedo, glm::vec3 emissive = glm::vec3(0.0f));
scene::Light point_light(float intensity);

// Six slabs `thickness` thick around the box [lo, hi], overlapping at the edges so that the
// inside is closed; their inner faces are the walls of a room [lo, hi].
void add_closed_box(scene::SceneBuilder& builder, glm::vec3 lo, glm::vec3 hi, float thickness,
                    int material);

// A floor with a box on it, lit by one point light, seen from `eye` (relative to `offset`,
// scaled) by a camera named `camera`; `offset` and `scale` move and size the whole thing.
scene::Scene lit_floor(const std::string& name, glm::vec3 offset, float scale,
                       glm::vec3 eye = glm::vec3(0.0f, 3.0f, 0.01f), const char* camera = "top",
                       const scene::Material& surface = matte(glm::vec3(0.8f)));

// Zero-area (repeated vertex), collinear and proper triangles, all normals zero.
scene::Scene degenerate_triangles(const scene::Material& surface = matte(glm::vec3(0.8f)));
// A 2 m floor crossed at x = 0 by a 1 m high wall of two faces 1 mm apart with opposite normals,
// facing away from each other (one voxel holds both, their normals cancel). A point light on
// the -x side; the camera "top" looks down on both sides.
scene::Scene thin_wall(const scene::Material& surface = matte(glm::vec3(0.8f)));
// One point light exactly on the floor and one inside the box.
scene::Scene light_on_a_surface_and_inside_geometry();
// Two emissive quads, one at 1e5 and one at 1e-5, and no lights.
scene::Scene very_bright_and_very_dim_emitters();
// The camera at the centre of a closed box room.
scene::Scene camera_inside_geometry();
// A directional light 1e-4 rad above the floor, seen from the floor's height.
scene::Scene grazing_light();
// A triangle under a node with a negative scale.
scene::Scene mirrored_node();

}  // namespace voxgi::test
