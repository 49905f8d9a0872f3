// Every file of the glTF corpus (tests/scene/gltf_corpus.hpp) loads with the warnings it must
// give, or is refused with one line that names the file and the feature. Prints the corpus
// table (file, features, result) that docs/inputs.md quotes.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <sstream>

#include "engine/scene/gltf_loader.hpp"
#include "tests/scene/gltf_corpus.hpp"
#include "tests/scene/gltf_writer.hpp"

namespace voxgi::scene {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void expect_sound(const Scene& scene, const std::string& file) {
  for (const Mesh& mesh : scene.meshes) {
    for (const Primitive& p : mesh.primitives) {
      for (const Vertex& v : p.vertices) {
        for (int k = 0; k < 3; ++k) {
          ASSERT_TRUE(std::isfinite(v.position[k]) && std::isfinite(v.normal[k])) << file;
        }
        for (int k = 0; k < 4; ++k) ASSERT_TRUE(v.color[k] >= 0.0f && v.color[k] <= 1.0f) << file;
      }
      for (uint32_t i : p.indices) ASSERT_LT(i, p.vertices.size()) << file;
      EXPECT_EQ(p.indices.size() % 3, 0u) << file;
    }
  }
}

TEST(GltfCorpus, EveryFileLoadsOrIsRefusedWithOneLine) {
  const std::filesystem::path dir = test::fresh_dir("gltf-corpus");
  std::ostringstream table;
  table << "| file | features | result |\n|---|---|---|\n";
  for (const test::GltfCorpusEntry& entry : test::gltf_corpus()) {
    SCOPED_TRACE(entry.file);
    const std::filesystem::path path = dir / entry.file;
    entry.write(path);
    std::string result;
    try {
      const Scene scene = load_gltf(path);
      EXPECT_TRUE(entry.refusal.empty()) << "loaded, expected a refusal naming " << entry.refusal;
      expect_sound(scene, entry.file);
      for (const std::string& part : entry.warnings) {
        bool found = false;
        for (const std::string& w : scene.warnings) found |= contains(w, part);
        EXPECT_TRUE(found) << "no warning names " << part;
      }
      for (const std::string& w : scene.warnings) EXPECT_FALSE(contains(w, "\n")) << w;
      const SceneFeatures features = scene.features();
      result = "loads: " + std::to_string(features.triangle_count) + " triangles, " +
               std::to_string(features.light_count) + " lights";
      if (!scene.warnings.empty()) {
        result += "; warns: " + scene.warnings.front() +
                  (scene.warnings.size() > 1
                       ? " (+" + std::to_string(scene.warnings.size() - 1) + " more)"
                       : "");
      }
    } catch (const SceneError& e) {
      const std::string message = e.what();
      EXPECT_FALSE(entry.refusal.empty()) << "refused: " << message;
      EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
      EXPECT_TRUE(contains(message, entry.refusal)) << message;
      EXPECT_FALSE(contains(message, "\n")) << message;
      result = "refused: " + message.substr(path.string().size() + 2);
    }
    table << "| " << entry.file << " | " << entry.features << " | " << result << " |\n";
  }
  std::cout << table.str();
  std::filesystem::remove_all(dir);
}

// EXT_mesh_gpu_instancing: one drawn instance per element, placed under the node.
TEST(GltfCorpus, GpuInstancingDrawsOneInstancePerElement) {
  const std::filesystem::path dir = test::fresh_dir("gltf-instancing");
  for (const test::GltfCorpusEntry& entry : test::gltf_corpus()) {
    if (entry.file != "gpu-instancing.gltf") continue;
    entry.write(dir / entry.file);
    const Scene scene = load_gltf(dir / entry.file);
    const std::vector<Instance> instances = scene.instances();
    ASSERT_EQ(instances.size(), 16u);
    // Instance 5: translation (-0.5, 0.5, -0.5), a quarter of the quad's 2 m side in x and z.
    const glm::mat4& world = instances[5].world;
    EXPECT_NEAR(world[3].x, -0.5f, 1e-5f);
    EXPECT_NEAR(world[3].y, 0.5f, 1e-5f);
    EXPECT_NEAR(world[3].z, -0.5f, 1e-5f);
    EXPECT_NEAR(glm::length(glm::vec3(world[0])), 0.2f, 1e-4f);
    EXPECT_NEAR(glm::length(glm::vec3(world[1])), 1.0f, 1e-4f);
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace voxgi::scene
