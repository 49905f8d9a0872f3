#pragma once
// A corpus of glTF files with the variety that exporters and asset pipelines write (interleaved
// and quantized vertices, vertex colours, two UV sets, texture transforms, embedded images,
// strips and fans, skins, morph targets, compressed-data extensions, ...). Each entry writes
// its file into a folder and says what loading it must give: the scene, with the warnings
// named, or one refusal naming the file and the feature. The CPU test loads every entry; a GPU
// test renders the ones that load.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace voxgi::test {

struct GltfCorpusEntry {
  std::string file;      // file name, .gltf or .glb
  std::string features;  // what it exercises, for the corpus table
  // Empty: the file loads. Otherwise a part of the one-line refusal (the feature's name).
  std::string refusal;
  std::vector<std::string> warnings;  // parts of warnings loading must give
  std::function<void(const std::filesystem::path& path)> write;
};

std::vector<GltfCorpusEntry> gltf_corpus();

}  // namespace voxgi::test
