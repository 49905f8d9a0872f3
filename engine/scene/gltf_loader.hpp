#pragma once
// glTF 2.0 (.gltf + buffers, or .glb) → Scene.

#include <filesystem>

#include "engine/scene/scene.hpp"

namespace voxgi::scene {

// Supported: node hierarchy (TRS and matrix), TRIANGLES primitives (other modes are skipped
// with a warning), POSITION/NORMAL/TANGENT/TEXCOORD_0 in every component type glTF allows,
// metallic-roughness materials with all five textures, KHR_materials_emissive_strength,
// KHR_lights_punctual, perspective cameras and TRS animations. Unsupported features and
// undecodable images become Scene::warnings. Malformed input throws SceneError whose
// message starts with the path and names the field, e.g.
// "x.gltf: meshes[2].primitives[0].attributes.POSITION: accessor 7 out of range (5 accessors)".
Scene load_gltf(const std::filesystem::path& path);

}  // namespace voxgi::scene
