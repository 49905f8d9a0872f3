// vct.inject on volumes the test writes, against the formula it implements:
//   L = albedo / pi * I / d^2 * cos + emission (point light, no shadow maps bound),
// with the normal-less rule (cos = 1), empty voxels black, NaN normals harmless, and the
// skip logic: a static frame skips, new voxels or changed lights run again.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

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

// A scene of one point light and no geometry: the voxels come from the test.
scene::Scene point_light_scene(glm::vec3 position, float intensity) {
  scene::SceneBuilder b("light");
  scene::Light light;
  light.type = scene::LightType::Point;
  light.intensity = intensity;
  b.add_light(light, position);
  return b.finish();
}

TEST_F(InjectTest, MatchesTheLambertFormulaAndSkipsStaticFrames) {
  const glm::vec3 light_position(0.0f, 0.6f, 0.0f);
  const float intensity = 3.0f;
  scene::Scene scene = point_light_scene(light_position, intensity);

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

// Light shares are per face group: asking for them without the faces is an error that names
// the slot, not a volume of zeros.
TEST_F(InjectTest, LightSharesWithoutFacesNamesTheField) {
  std::string graph = inject_graph();
  const std::string out = "\"out\": { \"radiance\": \"vct.radiance\" }";
  const std::string resources = "\"resources\": {\n";
  ASSERT_NE(graph.find(out), std::string::npos);
  graph.replace(graph.find(out), out.size(),
                "\"out\": { \"radiance\": \"vct.radiance\", \"light_shares\": \"vct.shares\" }");
  graph.insert(graph.find(resources) + resources.size(),
               "\"vct.shares\": { \"type\": \"clipmap\", \"resolution\": 16, \"levels\": 1, "
               "\"format\": \"r32ui\", \"persistent\": true },\n");
  VolumeData data;
  data.info = make_clipmap_info(kR, 1, kVoxel, glm::vec3(0.0f));
  try {
    VolumeGraph compiled(graph, &data, point_light_scene(glm::vec3(0.0f), 1.0f));
    FAIL() << "expected an error";
  } catch (const std::exception& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("light_shares"), std::string::npos) << message;
    EXPECT_NE(message.find("faces"), std::string::npos) << message;
  }
}

std::string faces_inject_graph() {
  const std::string clipmap =
      "{ \"type\": \"clipmap\", \"resolution\": 16, \"levels\": 1, \"persistent\": true, "
      "\"format\": ";
  std::string graph = "{ \"name\": \"vct-inject-faces-test\", \"resources\": {\n";
  for (const char* r : {"albedo:rgba8", "normal:rgba16f", "faces:rgba32ui"}) {
    const std::string spec(r);
    const size_t colon = spec.find(':');
    graph += "\"voxel." + spec.substr(0, colon) + "\": " + clipmap + "\"" + spec.substr(colon + 1) +
             "\" },\n";
  }
  graph += "\"vct.radiance\": " + clipmap + "\"rgba16f\" },\n";
  graph += "\"vct.light_shares\": " + clipmap + "\"r32ui\" },\n";
  graph +=
      "\"voxel.clipmap_info\": { \"type\": \"buffer\", \"size\": 288, \"persistent\": true } },\n"
      "\"passes\": [\n"
      " { \"name\": \"volumes\", \"type\": \"vcttest.volumes\", \"out\": { \"clipmap_info\": "
      "\"voxel.clipmap_info\", \"albedo\": \"voxel.albedo\", \"normal\": \"voxel.normal\", "
      "\"faces\": \"voxel.faces\" } },\n"
      " { \"name\": \"inject\", \"type\": \"vct.inject\", \"in\": { \"clipmap_info\": "
      "\"voxel.clipmap_info\", \"albedo\": \"voxel.albedo\", \"normal\": \"voxel.normal\", "
      "\"faces\": \"voxel.faces\" }, \"out\": { \"radiance\": \"vct.radiance\", "
      "\"light_shares\": \"vct.light_shares\" } } ],\n"
      "\"outputs\": { \"radiance\": \"vct.radiance\" } }\n";
  return graph;
}

// With the faces volume, each way a voxel's surfaces face is lit on its own (its normal, its
// cosine), weighted by its area share: a floor meeting a wall under a light above them, the two
// faces of a thin slab (the face turned away is dark; without faces the slab, whose normals
// cancel, was lit whole as if it faced the light), against the formula. The light shares say
// which group sends how much of it: all of the slab's from its lit face, so that vct.filter
// sends it that way only.
TEST_F(InjectTest, LightsEachFacingOfAVoxelOnItsOwn) {
  const glm::vec3 light_position(0.3f, 0.6f, 0.0f);
  const float intensity = 3.0f;
  scene::Scene scene = point_light_scene(light_position, intensity);

  VolumeData data;
  data.info = make_clipmap_info(kR, 1, kVoxel, glm::vec3(0.0f));
  CpuClipmap albedo(kR, 1), normal(kR, 1), faces(kR, 1);
  struct Voxel {
    const char* what;
    glm::ivec3 window;
    std::vector<std::pair<int, uint32_t>> groups;  // group (0..5 = +X..-Z), share in 31sts
  };
  const std::vector<Voxel> voxels = {
      {"floor meeting a wall", {8, 4, 8}, {{0, 10}, {2, 21}}},
      {"thin slab", {6, 4, 8}, {{2, 16}, {3, 15}}},
      {"floor", {10, 4, 8}, {{2, 31}}},
  };
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Voxel& v : voxels) {
    const glm::ivec3 t = clipmap_texel(data.info, v.window, 0);
    albedo.at(t) = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
    glm::vec3 mean(0.0f);
    for (const auto& [g, steps] : v.groups) mean += axes[g] * (float(steps) / 31.0f);
    normal.at(t) = glm::vec4(mean, 1.0f);  // plane offset 0: surfaces through the centre
    faces.at(t) = faces_texel(v.groups);
  }
  data.volumes["albedo"] = albedo;
  data.volumes["normal"] = normal;
  data.volumes["faces"] = faces;
  VolumeGraph graph(faces_inject_graph(), &data, scene);
  graph.render();
  const std::vector<glm::vec4> radiance = graph.download("vct.radiance");
  const std::vector<glm::vec4> light_shares = graph.download("vct.light_shares");

  const float a = std::round(0.6f * 255.0f) / 255.0f;
  for (const Voxel& v : voxels) {
    const glm::vec3 centre =
        glm::vec3(data.info.levels[0].min_corner_size) + (glm::vec3(v.window) + 0.5f) * kVoxel;
    const glm::vec3 to_light = light_position - centre;
    const float d2 = glm::dot(to_light, to_light);
    const glm::vec3 l = to_light / std::sqrt(d2);
    // Per group: L_g = a / pi I / d^2 max(n_g . l, 0); the voxel holds their share-weighted mean.
    float shares = 0.0f, mean = 0.0f;
    float group_light[6] = {};
    for (const auto& [g, steps] : v.groups) {
      const float s = float(steps) / 31.0f;
      group_light[g] = s * a / float(M_PI) * intensity / d2 * std::max(glm::dot(axes[g], l), 0.0f);
      mean += group_light[g];
      shares += s;
    }
    const float light = mean;
    mean /= shares;
    const size_t index = albedo.index(clipmap_texel(data.info, v.window, 0));
    std::printf("%s: radiance %.5f, expected %.5f\n", v.what, radiance[index].r, mean);
    EXPECT_NEAR(radiance[index].r, mean, 2e-3f + 2e-3f * mean) << v.what;
    const uint32_t bits = glm::floatBitsToUint(light_shares[index].x);
    for (int g = 0; g < 6; ++g) {
      const float share = float((bits >> (5 * g)) & 31u) / 31.0f;
      // 5 bits: within half a step of the exact share.
      EXPECT_NEAR(share, group_light[g] / light, 0.5f / 31.0f + 1e-4f) << v.what << ", group " << g;
    }
  }
}

}  // namespace
}  // namespace voxgi::test
