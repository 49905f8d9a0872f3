#pragma once
// Scene and graph sources as users name them: a built-in scene name or a glTF path, a camera
// name, a graph path, and "key=value" overrides.

#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/scene/scene.hpp"

namespace voxgi::runtime {

// A built-in scene ("cornell", ...) or a .gltf/.glb file, with transforms evaluated. Throws
// scene::SceneError naming the file (or the valid built-in names).
scene::Scene load_scene(const std::string& spec);

// The named camera, else the scene's first camera, else a camera framing the bounds. Throws
// std::invalid_argument listing the scene's cameras when `name` matches none.
scene::Camera choose_camera(const scene::Scene& scene, const std::string& name);

// A graph path as given, or, for a relative path that does not exist from the working
// directory, the same path inside the source tree (so `graphs/default.json` works anywhere).
std::filesystem::path resolve_graph_path(const std::string& arg);

// The source tree's root as built (graphs/, shaders/ live there).
std::filesystem::path repo_dir();

// A "key=value" string without '=' or with an empty key; `setting` is the string as given.
class OverrideError : public std::invalid_argument {
 public:
  explicit OverrideError(const std::string& bad_setting);
  std::string setting;
};

// "key=value" strings → overrides. Throws OverrideError naming the bad string.
std::map<std::string, std::string> parse_overrides(const std::vector<std::string>& settings);

}  // namespace voxgi::runtime
