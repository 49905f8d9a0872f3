// Shadow maps put points known to be occluded (segment to the light crosses the box) in
// shadow, and leave clearly unoccluded points lit, for each light type.

#include <gtest/gtest.h>

#include <string>

#include "brdf_reference.hpp"
#include "plane_scene_probe.hpp"
#include "render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

class ShadowMapsTest : public GpuTest, public ::testing::WithParamInterface<const char*> {};

TEST_P(ShadowMapsTest, OccludedPointsAreDark) {
  RenderSetup setup;
  setup.scene = GetParam();
  setup.overrides = {{"ambient.enabled", "false"}};
  RenderHarness harness(setup);
  harness.render();
  const RenderedImage image = harness.output("linear");
  const PlaneSceneProbe probe(harness.scene());
  const scene::Light& light = harness.scene().lights.at(0);

  int shadowed = 0, lit = 0;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const std::optional<glm::vec3> p =
          probe.floor_point(harness.view_proj(), x, y, image.width, image.height);
      if (!p) continue;
      glm::vec3 l;
      const float unshadowed = punctual_light_at(light, *p, l).g * std::max(l.y, 0.0f);
      if (unshadowed < 1e-3f) continue;  // outside a spot cone: no light either way
      const float got = image.at(x, y).g;
      if (probe.occluded(light, *p, -0.03f)) {
        ++shadowed;
        EXPECT_LT(got, 1e-4f) << GetParam() << ": occluded pixel (" << x << ", " << y
                              << ") is lit: " << got;
      } else if (!probe.occluded(light, *p, 0.08f)) {
        ++lit;
        EXPECT_GT(got, 0.05f * unshadowed)
            << GetParam() << ": unoccluded pixel (" << x << ", " << y << ") is dark";
      }
    }
  }
  EXPECT_GT(shadowed, 20) << GetParam() << ": the camera sees too little of the shadow";
  EXPECT_GT(lit, 100);
}

TEST_P(ShadowMapsTest, SwitchingShadowsOffLightsTheShadow) {
  RenderSetup setup;
  setup.scene = GetParam();
  setup.overrides = {{"ambient.enabled", "false"}, {"lighting.shadows", "false"}};
  RenderHarness harness(setup);
  harness.render();
  const RenderedImage image = harness.output("linear");
  const PlaneSceneProbe probe(harness.scene());
  const scene::Light& light = harness.scene().lights.at(0);
  int checked = 0;
  for (uint32_t y = 0; y < image.height; ++y) {
    for (uint32_t x = 0; x < image.width; ++x) {
      const std::optional<glm::vec3> p =
          probe.floor_point(harness.view_proj(), x, y, image.width, image.height);
      if (!p || !probe.occluded(light, *p, -0.03f)) continue;
      glm::vec3 l;
      if (punctual_light_at(light, *p, l).g < 1e-3f) continue;
      EXPECT_GT(image.at(x, y).g, 1e-4f);
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

INSTANTIATE_TEST_SUITE_P(PunctualLights, ShadowMapsTest, ::testing::ValuesIn(kPlaneScenes),
                         [](const auto& param_info) {
                           return plane_scene_test_name(param_info.param);
                         });

}  // namespace
}  // namespace voxgi::test
