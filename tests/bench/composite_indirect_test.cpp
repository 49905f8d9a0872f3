// The `indirect` output of common.composite, which benches compare with the reference's
// indirect light: it must be exactly what the composite added to the image.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "tests/common/render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

class CompositeIndirect : public GpuTest {};

// graphs/default.json with its direct and ambient images as extra outputs.
std::filesystem::path graph_with_parts() {
  std::ifstream in(std::filesystem::path(VOXGI_SOURCE_DIR) / "graphs" / "default.json");
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const size_t end = text.rfind('}');
  EXPECT_NE(end, std::string::npos) << "graphs/default.json is not an object";
  // Outputs join those the graph's fragments declare.
  text.insert(end,
              ",\n  \"outputs\": { \"direct\": \"light.direct\", \"ambient\": \"gi.diffuse\" }\n");
  const std::filesystem::path file = make_temp_dir("voxgi-composite") / "parts.json";
  std::ofstream(file) << text;
  return file;
}

// fp16 storage: about 3 significant digits.
bool close(float a, float b) {
  return std::fabs(a - b) <= 2e-3f * std::max(a, b) + 1e-5f;
}

TEST_F(CompositeIndirect, IsTheIndirectTermAsAddedWithScaleApplied) {
  RenderSetup setup;
  setup.graph = graph_with_parts().string();
  setup.width = 64;
  setup.height = 64;
  setup.overrides = {{"composite.indirect_scale", "2.5"}, {"ambient.radiance", "0.1"}};
  RenderHarness harness(setup);
  harness.render(1);
  const RenderedImage linear = harness.output("linear");
  const RenderedImage indirect = harness.output("indirect");
  const RenderedImage direct = harness.output("direct");
  const RenderedImage ambient = harness.output("ambient");
  expect_finite_non_negative(indirect, "indirect");
  size_t lit = 0, mismatched_sum = 0, mismatched_scale = 0;
  for (uint32_t y = 0; y < linear.height; ++y) {
    for (uint32_t x = 0; x < linear.width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const float i = indirect.at(x, y)[c];
        if (i > 0.0f) ++lit;
        if (!close(linear.at(x, y)[c], direct.at(x, y)[c] + i)) ++mismatched_sum;
        if (!close(i, 2.5f * ambient.at(x, y)[c])) ++mismatched_scale;
      }
    }
  }
  EXPECT_GT(lit, 64u * 64u) << "the ambient term lights the Cornell box";
  EXPECT_EQ(mismatched_sum, 0u) << "linear = direct + indirect";
  EXPECT_EQ(mismatched_scale, 0u) << "indirect = ambient x indirect_scale";
}

}  // namespace
}  // namespace voxgi::test
