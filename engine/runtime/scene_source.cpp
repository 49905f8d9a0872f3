#include "engine/runtime/scene_source.hpp"

#include <stdexcept>
#include <system_error>

#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/gltf_loader.hpp"

namespace voxgi::runtime {

scene::Scene load_scene(const std::string& spec) {
  const std::filesystem::path path(spec);
  const std::string ext = path.extension().string();
  scene::Scene loaded =
      (ext == ".gltf" || ext == ".glb") ? scene::load_gltf(path) : scene::make_builtin_scene(spec);
  loaded.update_transforms();
  return loaded;
}

scene::Camera choose_camera(const scene::Scene& scene, const std::string& name) {
  if (!name.empty()) {
    if (const scene::Camera* camera = scene.find_camera(name)) return *camera;
    std::string known;
    for (const scene::Camera& camera : scene.cameras)
      known += (known.empty() ? "" : ", ") + camera.name;
    throw std::invalid_argument("camera: scene '" + scene.source + "' has no camera '" + name +
                                "' (cameras: " + (known.empty() ? "none" : known) + ")");
  }
  if (!scene.cameras.empty()) return scene.cameras.front();
  return scene::default_camera(scene);
}

std::filesystem::path repo_dir() {
  return std::filesystem::path(VOXGI_REPO_DIR);
}

std::filesystem::path resolve_graph_path(const std::string& arg) {
  const std::filesystem::path path(arg);
  std::error_code ec;  // a name that cannot be looked up is one that does not exist
  if (std::filesystem::exists(path, ec) || path.is_absolute()) return path;
  const std::filesystem::path in_source = repo_dir() / path;
  return std::filesystem::exists(in_source, ec) ? in_source : path;
}

OverrideError::OverrideError(const std::string& bad_setting)
    : std::invalid_argument("set '" + bad_setting +
                            "': expected KEY=VALUE, e.g. lighting.pcf_radius=2"),
      setting(bad_setting) {}

std::map<std::string, std::string> parse_overrides(const std::vector<std::string>& settings) {
  std::map<std::string, std::string> overrides;
  for (const std::string& setting : settings) {
    const size_t eq = setting.find('=');
    if (eq == std::string::npos || eq == 0) throw OverrideError(setting);
    overrides[setting.substr(0, eq)] = setting.substr(eq + 1);
  }
  return overrides;
}

}  // namespace voxgi::runtime
