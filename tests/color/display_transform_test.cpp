#include <gtest/gtest.h>

#include <cmath>

#include "engine/color/display_transform.hpp"

namespace voxgi::color {
namespace {

const std::vector<glm::vec3> kSamples = {{0, 0, 0},
                                         {0.18f, 0.18f, 0.18f},
                                         {1, 1, 1},
                                         {16, 16, 16},
                                         {1, 0, 0},
                                         {0, 1, 0},
                                         {0, 0, 1},
                                         {4, 0.02f, 0.01f},
                                         {0.001f, 0.002f, 0.0005f},
                                         {0.5f, 0.25f, 0.8f},
                                         {0.05f, 0.3f, 0.05f},
                                         {100, 50, 10},
                                         {1e-6f, 0, 0},
                                         {2.5f, 2.5f, 0},
                                         {0.01f, 0.01f, 0.01f},
                                         {0.7f, 0.02f, 0.9f}};

TEST(DisplayTransform, ShippedConfigHasTheViews) {
  const DisplayTransform transform;
  const auto displays = transform.displays();
  ASSERT_NE(std::find(displays.begin(), displays.end(), "sRGB"), displays.end());
  const auto views = transform.views("sRGB");
  for (const char* view : {"Standard", "ACES 1.0 SDR-video", "Raw"}) {
    EXPECT_NE(std::find(views.begin(), views.end(), view), views.end()) << view;
  }
}

TEST(DisplayTransform, StandardIsClampedSrgb) {
  const DisplayTransform transform;
  for (float x : {0.0f, 0.002f, 0.18f, 0.5f, 1.0f, 4.0f}) {
    const float linear = std::min(x, 1.0f);
    const float expected =
        linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
    EXPECT_NEAR(transform.apply_cpu("sRGB", "Standard", glm::vec3(x)).g, expected, 1e-4f) << x;
  }
  const glm::vec3 aces = transform.apply_cpu("sRGB", "ACES 1.0 SDR-video", glm::vec3(0.18f));
  EXPECT_GT(aces.g, 0.3f);  // a tone curve, not an identity
  EXPECT_LT(aces.g, 0.5f);
  EXPECT_EQ(transform.apply_cpu("sRGB", "Raw", glm::vec3(3, 2, 1)), glm::vec3(3, 2, 1));
}

class LutMatchesOcio : public ::testing::TestWithParam<const char*> {};

TEST_P(LutMatchesOcio, WithinHalfAnEightBitCode) {
  const DisplayTransform transform;
  const DisplayTransform::Lut lut = transform.bake("sRGB", GetParam());
  ASSERT_EQ(lut.size, 65u);
  ASSERT_EQ(lut.rgba.size(), 65u * 65u * 65u * 4u);
  for (const glm::vec3& x : kSamples) {
    const glm::vec3 truth = transform.apply_cpu("sRGB", GetParam(), x);
    const glm::vec3 baked = DisplayTransform::apply_lut(lut, x);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(baked[c], truth[c], 0.5f / 255.0f)
          << GetParam() << " at (" << x.r << ", " << x.g << ", " << x.b << ") channel " << c;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Views, LutMatchesOcio, ::testing::Values("Standard", "ACES 1.0 SDR-video"),
                         [](const auto& param_info) {
                           return std::string(param_info.param[0] == 'S' ? "Standard" : "Aces");
                         });

TEST(DisplayTransform, BlackStaysBlackAndBadValuesAreSafe) {
  const DisplayTransform transform;
  for (const char* view : {"Standard", "ACES 1.0 SDR-video"}) {
    const auto lut = transform.bake("sRGB", view, 33);
    const glm::vec3 black = DisplayTransform::apply_lut(lut, glm::vec3(0.0f));
    EXPECT_LT(std::max(black.r, std::max(black.g, black.b)), 0.5f / 255.0f) << view;
    const glm::vec3 negative = DisplayTransform::apply_lut(lut, glm::vec3(-5.0f));
    EXPECT_EQ(negative, black);
    const glm::vec3 nan = DisplayTransform::apply_lut(lut, glm::vec3(std::nanf("")));
    EXPECT_EQ(nan, black);
    const glm::vec3 huge = DisplayTransform::apply_lut(lut, glm::vec3(1e30f));
    EXPECT_TRUE(std::isfinite(huge.r) && huge.r <= 1.0f);
  }
}

TEST(DisplayTransform, ShaperIsMonotonicAndContinuous) {
  DisplayTransform::Lut lut;
  lut.size = 65;
  float previous = -1.0f;
  for (float log2x = -20.0f; log2x < 9.0f; log2x += 0.01f) {
    const float t = DisplayTransform::shaper(lut, std::exp2(log2x));
    EXPECT_GE(t, previous);
    previous = t;
  }
  const float lo = std::exp2(lut.shaper_min_log2);
  EXPECT_NEAR(DisplayTransform::shaper(lut, lo * 0.9999f), DisplayTransform::shaper(lut, lo),
              1e-5f);
  EXPECT_NEAR(DisplayTransform::shaper(lut, lo), 1.0f / 64.0f, 1e-6f);
  EXPECT_NEAR(DisplayTransform::shaper(lut, 1.0f) * 64.0f, 43.0f, 1e-4f);  // x = 1 on a texel
  EXPECT_EQ(DisplayTransform::shaper(lut, 0.0f), 0.0f);
}

TEST(DisplayTransform, BadNamesListTheValidOnes) {
  const DisplayTransform transform;
  try {
    transform.bake("sRGB", "Filmic");
    FAIL();
  } catch (const ColorError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("config.ocio"), std::string::npos) << message;
    EXPECT_NE(message.find("Filmic"), std::string::npos) << message;
    EXPECT_NE(message.find("Standard"), std::string::npos) << message;
    EXPECT_NE(message.find("ACES 1.0 SDR-video"), std::string::npos) << message;
  }
  try {
    transform.apply_cpu("P3", "Standard", glm::vec3(1));
    FAIL();
  } catch (const ColorError& e) {
    EXPECT_NE(std::string(e.what()).find("sRGB"), std::string::npos) << e.what();
  }
  EXPECT_THROW(transform.views("nope"), ColorError);
  EXPECT_THROW(transform.bake("sRGB", "Standard", 1), ColorError);
}

TEST(DisplayTransform, MissingOrBrokenConfig) {
  EXPECT_THROW(DisplayTransform("/nonexistent/config.ocio"), ColorError);
  const auto path = std::filesystem::temp_directory_path() / "voxgi-broken.ocio";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("ocio_profile_version: 2\nroles: [\n", f);
    std::fclose(f);
  }
  try {
    DisplayTransform broken(path);
    FAIL();
  } catch (const ColorError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace voxgi::color
