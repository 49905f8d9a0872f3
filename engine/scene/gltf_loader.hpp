#pragma once
// glTF 2.0 (.gltf + buffers, or .glb) → Scene.

#include <filesystem>

#include "engine/scene/scene.hpp"

namespace voxgi::scene {

// Supported: node hierarchy (TRS and matrix), triangle primitives (lists, strips and fans;
// points and lines are skipped with a warning), POSITION/NORMAL/TANGENT/TEXCOORD_0/TEXCOORD_1/
// COLOR_0 in every component type glTF allows (KHR_mesh_quantization's too), metallic-roughness
// materials with all five textures, each on either TEXCOORD set and with KHR_texture_transform,
// alpha modes, KHR_materials_emissive_strength, KHR_lights_punctual, perspective cameras and
// TRS animations. Skins and morph targets are drawn in the rest pose with a warning. An
// extension the file requires and voxgi lacks (Draco, meshopt, KTX2, ...) refuses the file
// naming it; one it only uses is a warning. Unsupported features and
// undecodable images become Scene::warnings. Malformed input throws SceneError whose
// message starts with the path and names the field, e.g.
// "x.gltf: meshes[2].primitives[0].attributes.POSITION: accessor 7 out of range (5 accessors)".
Scene load_gltf(const std::filesystem::path& path);

}  // namespace voxgi::scene
