#include "apps/voxgi/scene_source.hpp"

#include <filesystem>
#include <stdexcept>

#include "engine/scene/builtin_scenes.hpp"
#include "engine/scene/gltf_loader.hpp"

namespace voxgi::cli {

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
    throw std::invalid_argument("--camera: scene '" + scene.source + "' has no camera '" + name +
                                "' (cameras: " + (known.empty() ? "none" : known) + ")");
  }
  if (!scene.cameras.empty()) return scene.cameras.front();
  return scene::default_camera(scene);
}

}  // namespace voxgi::cli
