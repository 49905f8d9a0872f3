// vct.inject on volumes the test writes, against the formula it implements:
//   L = albedo / pi * I / d^2 * cos + emission (point light, no shadow maps bound),
// with the normal-less rule (cos = 1), empty voxels black, NaN normals harmless, and the
// skip logic: a static frame skips, new voxels or changed lights run again.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "engine/scene/scene_builder.hpp"
#include "tests/gpu/gpu_test_env.hpp"
#include "tests/vct/volume_harness.hpp"

namespace voxgi::test {
namespace {

constexpr int kR = 16;
constexpr float kVoxel = 0.125f;  // a 2 m volume around the origin

std::string inject_graph() {
  const std::string clipmap =
      "{ \"type\": \"clipmap\", \"resolution\": 16, \"levels\": 1, \"persistent\": true, "
      "\"format\": ";
  return "{ \"name\": \"vct-inject-test\", \"resources\": {\n"
         "\"voxel.clipmap_info\": { \"type\": \"buffer\", \"size\": 288, \"persistent\": true },\n"
         "\"voxel.albedo\": " +
         clipmap +
         "\"rgba8\" },\n"
         "\"voxel.normal\": " +
         clipmap +
         "\"rgba16f\" },\n"
         "\"voxel.emission\": " +
         clipmap +
         "\"rgba16f\" },\n"
         "\"vct.radiance\": " +
         clipmap +
         "\"rgba16f\" } },\n"
         "\"passes\": [\n"
         " { \"name\": \"volumes\", \"type\": \"vcttest.volumes\", \"out\": { \"clipmap_info\": "
         "\"voxel.clipmap_info\", \"albedo\": \"voxel.albedo\", \"normal\": \"voxel.normal\", "
         "\"emission\": \"voxel.emission\" } },\n"
         " { \"name\": \"inject\", \"type\": \"vct.inject\", \"in\": { \"clipmap_info\": "
         "\"voxel.clipmap_info\", \"albedo\": \"voxel.albedo\", \"normal\": \"voxel.normal\", "
         "\"emission\": \"voxel.emission\" }, \"out\": { \"radiance\": \"vct.radiance\" } } ],\n"
         "\"outputs\": { \"radiance\": \"vct.radiance\" } }\n";
}

class InjectTest : public GpuTest {};

TEST_F(InjectTest, MatchesTheLambertFormulaAndSkipsStaticFrames) {
  const glm::vec3 light_position(0.0f, 0.6f, 0.0f);
  const float intensity = 3.0f;
  scene::SceneBuilder b("light");
  scene::Light light;
  light.type = scene::LightType::Point;
  light.intensity = intensity;
  b.add_light(light, light_position);
  scene::Scene scene = b.finish();

  VolumeData data;
  data.info = make_clipmap_info(kR, 1, kVoxel, glm::vec3(0.0f));
  CpuClipmap albedo(kR, 1), normal(kR, 1), emission(kR, 1);
  struct Voxel {
    glm::ivec3 window;
    glm::vec4 albedo;
    glm::vec4 normal;
    glm::vec3 emission;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Voxel> voxels = {
      {{8, 4, 8}, {0.5f, 0.25f, 1.0f, 1.0f}, {0, 1, 0, 1}, {0, 0, 0}},       // facing up
      {{10, 4, 8}, {1.0f, 1.0f, 1.0f, 1.0f}, {0, -1, 0, 1}, {0, 0, 0}},      // facing away
      {{6, 4, 8}, {0.8f, 0.8f, 0.8f, 1.0f}, {0, 0, 0, 1}, {0, 0, 0}},        // faces cancel
      {{8, 4, 5}, {0.6f, 0.6f, 0.6f, 0.5f}, {0.6f, 0.8f, 0, 1}, {2, 0, 0}},  // emissive
      {{3, 3, 3}, {0.6f, 0.6f, 0.6f, 1.0f}, {nan, nan, nan, 1}, {0, 0, 0}},  // NaN normal
  };
  for (const Voxel& v : voxels) {
    const glm::ivec3 t = clipmap_texel(data.info, v.window, 0);
    albedo.at(t) = v.albedo;
    normal.at(t) = v.normal;
    emission.at(t) = glm::vec4(v.emission, 0.0f);
  }
  data.volumes["albedo"] = albedo;
  data.volumes["normal"] = normal;
  data.volumes["emission"] = emission;
  VolumeGraph graph(inject_graph(), &data, scene);
  graph.render();
  const std::vector<glm::vec4> radiance = graph.download("vct.radiance");

  for (const Voxel& v : voxels) {
    const glm::vec3 centre =
        glm::vec3(data.info.levels[0].min_corner_size) + (glm::vec3(v.window) + 0.5f) * kVoxel;
    const glm::vec3 to_light = light_position - centre;
    const float d2 = glm::dot(to_light, to_light);
    const glm::vec3 l = to_light / std::sqrt(d2);
    const glm::vec3 n = glm::vec3(v.normal);
    const bool has_normal = std::isfinite(n.x) && glm::length(n) >= 0.25f;
    const float cos_theta = has_normal ? std::max(glm::dot(glm::normalize(n), l), 0.0f) : 1.0f;
    // rgba8 albedo as the GPU reads it.
    const glm::vec3 a = glm::round(glm::vec3(v.albedo) * 255.0f) / 255.0f;
    const glm::vec3 expected = a / float(M_PI) * (intensity / d2) * cos_theta + v.emission;
    const glm::vec4 got = radiance[albedo.index(clipmap_texel(data.info, v.window, 0))];
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(got[c], expected[c], 2e-3f + 2e-3f * expected[c])
          << "voxel " << v.window.x << "," << v.window.y << "," << v.window.z << " channel " << c;
    }
    EXPECT_NEAR(got.a, std::round(v.albedo.a * 255.0f) / 255.0f, 1e-3f);
  }
  size_t lit = 0;
  for (const glm::vec4& t : radiance) {
    ASSERT_TRUE(std::isfinite(t.r) && std::isfinite(t.g) && std::isfinite(t.b));
    if (t.a > 0.0f) ++lit;
  }
  EXPECT_EQ(lit, voxels.size()) << "empty voxels must stay empty";

  graph.render();
  EXPECT_EQ(graph.skipped("inject"), "voxels, shadow maps and lights unchanged");
  ++data.version;
  graph.render();
  EXPECT_EQ(graph.skipped("inject"), "");
  graph.render(1, /*lights_changed=*/true);
  EXPECT_EQ(graph.skipped("inject"), "");
}

}  // namespace
}  // namespace voxgi::test
