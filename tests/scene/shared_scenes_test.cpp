#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "engine/scene/gltf_loader.hpp"

namespace voxgi::scene {
namespace {

struct SharedScene {
  const char* file;
  uint32_t triangles;
  glm::vec3 min, max;
};

// The table of shared/scenes/README.md.
const SharedScene kScenes[] = {
    {"cornell-box/cornell-box.gltf", 36, {0, 0, 0}, {0.556f, 0.5488f, 0.5592f}},
    {"sibenik/sibenik.glb", 76529, {-58.0f, -2.0f, -35.0f}, {68.0f, 30.6f, 45.0f}},
    {"conference/conference.glb", 69047, {-1020.1f, -2.8f, -1055.7f}, {1685.8f, 650.3f, 668.5f}},
    {"sponza-dabrovic/sponza-dabrovic.glb",
     66450,
     {-17.40f, -0.91f, -7.80f},
     {17.42f, 15.65f, 7.80f}},
};

class SharedScenes : public ::testing::TestWithParam<SharedScene> {};

TEST_P(SharedScenes, LoadWithTheDocumentedCountsAndBounds) {
  const std::filesystem::path path =
      std::filesystem::path(VOXGI_SHARED_DIR) / "scenes" / GetParam().file;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared scene not available: " << path;
  const Scene scene = load_gltf(path);
  const SceneFeatures f = scene.features();
  EXPECT_EQ(f.triangle_count, GetParam().triangles);
  // The README rounds its bounds; allow that rounding plus 1e-3 of the extent.
  const glm::vec3 extent = GetParam().max - GetParam().min;
  const float tolerance = 1e-3f * std::max(extent.x, std::max(extent.y, extent.z)) + 0.005f;
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(f.bounds_min[c], GetParam().min[c], tolerance) << c;
    EXPECT_NEAR(f.bounds_max[c], GetParam().max[c], tolerance) << c;
  }
  for (const Mesh& mesh : scene.meshes) {
    for (const Primitive& p : mesh.primitives) {
      for (const Vertex& v : p.vertices) {
        ASSERT_TRUE(std::isfinite(v.normal.x + v.normal.y + v.normal.z));
        ASSERT_TRUE(std::isfinite(v.tangent.x + v.tangent.y + v.tangent.z + v.tangent.w));
        ASSERT_NEAR(glm::length(v.normal), 1.0f, 1e-3f);
      }
    }
  }
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();
}

INSTANTIATE_TEST_SUITE_P(All, SharedScenes, ::testing::ValuesIn(kScenes),
                         [](const auto& param_info) {
                           std::string name =
                               std::filesystem::path(param_info.param.file).stem().string();
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(SharedScenesCornell, HasItsCameraAndEmitter) {
  const std::filesystem::path path =
      std::filesystem::path(VOXGI_SHARED_DIR) / "scenes/cornell-box/cornell-box.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared scene not available: " << path;
  const Scene scene = load_gltf(path);
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_NEAR(scene.cameras[0].world[3].z, -0.8f, 1e-6f);
  const glm::vec3 forward = glm::vec3(scene.cameras[0].world * glm::vec4(0, 0, -1, 0));
  EXPECT_NEAR(forward.z, 1.0f, 1e-6f);
  bool emitter = false;
  for (const Material& m : scene.materials) {
    if (std::abs(m.emissive.r - 17.0f) < 1e-4f && std::abs(m.emissive.g - 12.0f) < 1e-4f)
      emitter = true;
  }
  EXPECT_TRUE(emitter);
}

}  // namespace
}  // namespace voxgi::scene
