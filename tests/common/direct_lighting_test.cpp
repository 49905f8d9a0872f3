// Direct lighting on a plane under a point, a spot and a directional light matches the glTF
// BRDF evaluated on the CPU (brdf_reference.hpp) within 1% at every lit sample pixel.

#include <gtest/gtest.h>

#include <string>

#include "brdf_reference.hpp"
#include "plane_scene_probe.hpp"
#include "render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

class DirectLightingTest : public GpuTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(DirectLightingTest, MatchesCpuBrdfWithinOnePercent) {
  RenderSetup setup;
  setup.scene = GetParam();
  setup.overrides = {{"ambient.enabled", "false"}};
  RenderHarness harness(setup);
  harness.render();
  const RenderedImage image = harness.output("linear");

  const PlaneSceneProbe probe(harness.scene());
  ASSERT_EQ(harness.scene().lights.size(), 1u);
  const scene::Light& light = harness.scene().lights[0];
  const scene::Material& material = probe.floor_material();
  const glm::vec3 eye = glm::vec3(harness.camera().world[3]);
  const glm::vec3 n(0.0f, 1.0f, 0.0f);

  int compared = 0, lit = 0;
  double worst = 0.0;
  for (uint32_t y = 1; y < image.height; y += 3) {
    for (uint32_t x = 1; x < image.width; x += 3) {
      const std::optional<glm::vec3> p =
          probe.floor_point(harness.view_proj(), x, y, image.width, image.height);
      if (!p || probe.occluded(light, *p, 0.08f)) continue;
      glm::vec3 l;
      const glm::vec3 e = punctual_light_at(light, *p, l);
      const glm::vec3 v = glm::normalize(eye - *p);
      const glm::vec3 expected = gltf_brdf(glm::vec3(material.base_color), material.metallic,
                                           material.roughness, n, v, l) *
                                 e * std::max(glm::dot(n, l), 0.0f);
      const glm::vec4 got = image.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const double scale = std::max<double>(expected[c], 1e-3);
        const double error = std::abs(got[c] - expected[c]) / scale;
        worst = std::max(worst, error);
        EXPECT_LT(error, 0.01) << GetParam() << " pixel (" << x << ", " << y << ") channel " << c
                               << ": got " << got[c] << ", expected " << expected[c];
      }
      ++compared;
      if (expected.g > 1e-3f) ++lit;
    }
  }
  EXPECT_GT(compared, 100) << "too few plane pixels compared";
  EXPECT_GT(lit, 50) << "too few lit pixels compared";
  std::cout << GetParam() << ": " << compared << " pixels, worst relative error " << worst << "\n";
}

INSTANTIATE_TEST_SUITE_P(PunctualLights, DirectLightingTest, ::testing::ValuesIn(kPlaneScenes),
                         [](const auto& param_info) {
                           return plane_scene_test_name(param_info.param);
                         });

}  // namespace
}  // namespace voxgi::test
