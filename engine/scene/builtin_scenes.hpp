#pragma once
// Procedural scenes addressed as "builtin:<name>" by the apps and used by tests.

#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/scene.hpp"

namespace voxgi::scene {

// "cornell", "plane-point", "plane-spot", "plane-directional", "empty".
std::vector<std::string> builtin_scene_names();
// Throws SceneError listing the valid names when `name` is not one of them.
Scene make_builtin_scene(std::string_view name);

}  // namespace voxgi::scene
