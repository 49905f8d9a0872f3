#pragma once
// Turns a --scene argument (a built-in name or a .gltf/.glb path) and a --camera name into a
// loaded scene and camera.

#include <string>

#include "engine/scene/scene.hpp"

namespace voxgi::cli {

// Throws scene::SceneError naming the file (or the valid built-in names).
scene::Scene load_scene(const std::string& spec);

// The named camera, else the scene's first camera, else a camera framing the bounds. Throws
// std::invalid_argument listing the scene's cameras when `name` matches none.
scene::Camera choose_camera(const scene::Scene& scene, const std::string& name);

}  // namespace voxgi::cli
