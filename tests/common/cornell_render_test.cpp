// The default graph on the Cornell box and on the hard cases the foundation can already run:
// finite, non-negative output, the walls on the right sides, identical static frames.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

glm::vec3 mean_over(const RenderedImage& image, uint32_t x0, uint32_t x1, uint32_t y0,
                    uint32_t y1) {
  glm::vec3 sum(0.0f);
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = x0; x < x1; ++x) sum += glm::vec3(image.at(x, y));
  return sum / static_cast<float>((x1 - x0) * (y1 - y0));
}

class CornellRenderTest : public GpuTest {};

TEST_F(CornellRenderTest, BuiltinCornellIsFiniteAndOriented) {
  RenderHarness harness(RenderSetup{});
  harness.render();
  const RenderedImage linear = harness.output("linear");
  const RenderedImage display = harness.output("display");
  ASSERT_EQ(linear.width, 128u);
  expect_finite_non_negative(linear, "linear");
  expect_finite_non_negative(display, "display");
  for (float v : display.rgba) ASSERT_LE(v, 1.0f);

  // Looking down +Z, the red wall (+X) is on the left and the green one on the right.
  const glm::vec3 left = mean_over(linear, 2, 14, 40, 90);
  const glm::vec3 right = mean_over(linear, 114, 126, 40, 90);
  EXPECT_GT(left.r, 2.0f * left.g) << "left wall should be red";
  EXPECT_GT(right.g, 2.0f * right.r) << "right wall should be green";
  // The ceiling light's emission (17, 12, 4) reaches the image unclipped (plus the specular
  // reflection of the point light just below it).
  float brightest = 0.0f;
  for (size_t i = 0; i < linear.rgba.size(); i += 4)
    brightest = std::max(brightest, linear.rgba[i]);
  EXPECT_GE(brightest, 16.9f);
}

TEST_F(CornellRenderTest, StaticFramesAreIdentical) {
  RenderHarness harness(RenderSetup{});
  harness.render();
  const RenderedImage first = harness.output("linear");
  harness.render(2);
  const RenderedImage third = harness.output("linear");
  ASSERT_EQ(first.rgba.size(), third.rgba.size());
  EXPECT_TRUE(first.rgba == third.rgba) << "a static scene must render bit-identical frames";
  bool shadows_skipped = false;
  for (const auto& timing : harness.executor().timings()) {
    if (timing.pass == "shadows") shadows_skipped = !timing.skipped.empty();
  }
  EXPECT_TRUE(shadows_skipped) << "unchanged shadow maps should not be re-rendered";
}

TEST_F(CornellRenderTest, EmptySceneRenders) {
  RenderSetup setup;
  setup.scene = "empty";
  RenderHarness harness(setup);
  harness.render();
  expect_finite_non_negative(harness.output("linear"), "empty scene");
}

TEST_F(CornellRenderTest, SharedCornellBoxWithOnlyAnEmitterRenders) {
  const std::filesystem::path file =
      std::filesystem::path(VOXGI_SHARED_DIR) / "scenes/cornell-box/cornell-box.gltf";
  if (!std::filesystem::exists(file)) {
    GTEST_SKIP() << "shared scenes not present (" << file << "); skipping";
  }
  RenderSetup setup;
  setup.scene = file.string();
  RenderHarness harness(setup);
  ASSERT_NE(harness.compiled().find_culled("shadows"), nullptr)
      << "a scene without punctual lights needs no shadow maps";
  harness.render();
  const RenderedImage linear = harness.output("linear");
  expect_finite_non_negative(linear, "shared cornell box");
  float brightest = 0.0f;
  for (size_t i = 0; i < linear.rgba.size(); i += 4)
    brightest = std::max(brightest, linear.rgba[i]);
  EXPECT_NEAR(brightest, 17.0f, 0.5f) << "the emitter's radiance should show as is";
}

}  // namespace
}  // namespace voxgi::test
