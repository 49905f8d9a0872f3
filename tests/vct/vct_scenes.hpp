#pragma once
// Scenes the vct graph tests build: the white-furnace box and the two-room leak test.

#include "engine/scene/scene.hpp"

namespace voxgi::test {

// A closed 1 m box of thick walls (albedo 1, emission le), no lights, camera inside. With
// `metal_floor` the floor is a white metal (base colour 1, metallic 1, roughness 0.2) that
// reflects only through the specular cone.
scene::Scene furnace_box(float le, bool metal_floor = false);

// Level-0 voxel edge of the two-room scene; its partition is one voxel thick.
inline constexpr float kTwoRoomsVoxel = 0.04f;
// Two 1 m rooms side by side along x, partition of one voxel at x = 1, a point light in room
// 0; the camera stands in room `camera_room` looking at that room's end wall.
scene::Scene two_rooms(int camera_room);

}  // namespace voxgi::test
