#pragma once
// glTF 2.0 allows some things its parser (tinygltf) refuses. Before parsing, the loader rewrites
// the JSON of a .gltf or of a GLB's JSON chunk into an equivalent document the parser takes,
// and reports each rewrite as a warning.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace voxgi::scene {

struct NormalizedGltf {
  bool changed = false;               // false: use the document as it was
  std::string json;                   // the rewritten document, when changed
  std::vector<std::string> warnings;  // one per rewrite that changes meaning, naming the field
};

// Rewrites, where present: numbers with integral values written as floats (3.0) become
// integers (silently: float fields read them the same); a skin without
// inverseBindMatrices (identity by the specification; voxgi draws skins in bind pose) is
// dropped; a buffer with no uri that is not a GLB's binary chunk becomes zeros of its
// byteLength (at most 64 MiB); animation channels whose target names no node (as
// KHR_animation_pointer writes them) are dropped. std::nullopt when `json` is not JSON: the
// parser's own message then says why.
std::optional<NormalizedGltf> normalize_gltf_json(const std::string& json, bool glb);

// "buffers[0].uri: file 'x.bin' not found in DIR" for every buffer or image uri (not a data URI)
// that names no file next to the document: the parser's own message names neither the field
// nor the folder.
std::vector<std::string> missing_referenced_files(const std::string& json,
                                                  const std::filesystem::path& base_dir);

// A GLB with its JSON chunk replaced by `json` (padded with spaces), the other chunks kept.
// std::nullopt when `glb` is not a well-formed GLB container.
std::optional<std::vector<unsigned char>> replace_glb_json(const std::vector<unsigned char>& glb,
                                                           const std::string& json);

}  // namespace voxgi::scene
