// Image metrics against values worked out by hand on tiny images.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "engine/image/error_map.hpp"
#include "engine/image/metrics.hpp"
#include "tests/image/filled_image.hpp"

namespace voxgi::image {
namespace {

TEST(ImageMetrics, IdenticalImagesHaveNoError) {
  const ImageRGBA32F a = filled(16, 16, 0.2f, 0.5f, 3.0f);
  const ImageMetrics m = compare_images(a, a);
  EXPECT_DOUBLE_EQ(m.rmse, 0.0);
  EXPECT_DOUBLE_EQ(m.rel_mse, 0.0);
  EXPECT_NEAR(m.ssim_luminance, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(m.luminance_bias, 0.0);
  EXPECT_DOUBLE_EQ(m.hdr_flip, 0.0);
  EXPECT_EQ(m.compared_pixels, 256u);
}

TEST(ImageMetrics, HandComputedValuesOnTwoPixels) {
  // Reference: (1, 1, 1) and (0, 0, 0). Image: (1.5, 1, 1) and (0.1, 0.1, 0.1).
  ImageRGBA32F reference = filled(2, 1, 0, 0, 0);
  ImageRGBA32F image = filled(2, 1, 0, 0, 0);
  for (int c = 0; c < 3; ++c) reference.at(0, 0)[c] = 1.0f;
  image.at(0, 0)[0] = 1.5f;
  image.at(0, 0)[1] = 1.0f;
  image.at(0, 0)[2] = 1.0f;
  for (int c = 0; c < 3; ++c) image.at(1, 0)[c] = 0.1f;
  const ImageMetrics m = compare_images(image, reference);
  // squared errors: 0.25, 0, 0, 0.01, 0.01, 0.01 → mean 0.28 / 6
  EXPECT_NEAR(m.rmse, std::sqrt(0.28 / 6.0), 1e-6);
  // relative: 0.25 / 1.01 + 3 * 0.01 / 0.01 = 0.247525 + 3 → / 6
  EXPECT_NEAR(m.rel_mse, (0.25 / 1.01 + 3.0) / 6.0, 1e-6);
  // luminance: image (0.2126 * 1.5 + 0.7152 + 0.0722 + 0.1) / 2, reference 0.5
  const double image_y = (0.2126 * 1.5 + 0.7152 + 0.0722 + 0.1) / 2.0;
  EXPECT_NEAR(m.mean_luminance, image_y, 1e-6);
  EXPECT_NEAR(m.mean_luminance_reference, 0.5, 1e-6);
  EXPECT_NEAR(m.luminance_bias, (image_y - 0.5) / 0.5, 1e-6);
  EXPECT_GT(m.luminance_bias, 0.0) << "a brighter image has a positive bias";
}

TEST(ImageMetrics, TooDarkGivesNegativeBias) {
  const ImageMetrics m = compare_images(filled(8, 8, 0.5f, 0.5f, 0.5f), filled(8, 8, 1, 1, 1));
  EXPECT_NEAR(m.luminance_bias, -0.5, 1e-6);
}

TEST(ImageMetrics, MeanLuminanceLeavesNonFinitePixelsOut) {
  ImageRGBA32F image = filled(2, 1, 1, 1, 1);
  EXPECT_NEAR(mean_luminance(image), 1.0, 1e-12);
  image.at(1, 0)[0] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NEAR(mean_luminance(image), 1.0, 1e-12);
  EXPECT_EQ(mean_luminance(ImageRGBA32F()), 0.0);
}

TEST(ImageMetrics, SsimOfAConstantShiftMatchesTheFormula) {
  // Constant images: variances and covariance vanish, so SSIM is the luminance term
  // (2 μa μb + C1) / (μa² + μb² + C1) on the compressed luminances y / (1 + y).
  const ImageMetrics m = compare_images(filled(12, 12, 1, 1, 1), filled(12, 12, 3, 3, 3));
  const double a = 1.0 / 2.0, b = 3.0 / 4.0, c1 = 1e-4;
  EXPECT_NEAR(m.ssim_luminance, (2 * a * b + c1) / (a * a + b * b + c1), 1e-9);
}

TEST(ImageMetrics, SsimDropsForNoiseButNotForIdenticalStructure) {
  ImageRGBA32F checker = filled(32, 32, 0, 0, 0), noisy = filled(32, 32, 0, 0, 0);
  for (uint32_t y = 0; y < 32; ++y) {
    for (uint32_t x = 0; x < 32; ++x) {
      const float v = ((x / 4 + y / 4) % 2) ? 1.0f : 0.1f;
      for (int c = 0; c < 3; ++c) checker.at(x, y)[c] = v;
      const float n = ((x * 7 + y * 13) % 5) * 0.2f;
      for (int c = 0; c < 3; ++c) noisy.at(x, y)[c] = n;
    }
  }
  EXPECT_NEAR(compare_images(checker, checker).ssim_luminance, 1.0, 1e-12);
  EXPECT_LT(compare_images(noisy, checker).ssim_luminance, 0.5);
  // HDR-FLIP sees the same difference (flip_test.cpp tests it on its own).
  EXPECT_GT(compare_images(noisy, checker).hdr_flip, 0.1);
}

TEST(ImageMetrics, NonFinitePixelsAreCountedNotAveraged) {
  ImageRGBA32F image = filled(4, 4, 1, 1, 1), reference = filled(4, 4, 1, 1, 1);
  image.at(1, 1)[0] = std::numeric_limits<float>::quiet_NaN();
  image.at(2, 2)[1] = std::numeric_limits<float>::infinity();
  reference.at(3, 3)[2] = -std::numeric_limits<float>::infinity();
  const ImageMetrics m = compare_images(image, reference);
  EXPECT_EQ(m.non_finite_pixels, 2u);
  EXPECT_EQ(m.non_finite_reference_pixels, 1u);
  EXPECT_EQ(m.compared_pixels, 13u);
  EXPECT_DOUBLE_EQ(m.rmse, 0.0);
  EXPECT_TRUE(std::isfinite(m.ssim_luminance));
}

TEST(ImageMetrics, MismatchedSizesAreRejected) {
  EXPECT_THROW(compare_images(filled(2, 2, 0, 0, 0), filled(2, 3, 0, 0, 0)), std::invalid_argument);
  EXPECT_THROW(compare_images(ImageRGBA32F(), ImageRGBA32F()), std::invalid_argument);
}

TEST(ImageMetrics, RmseOfAConstantOffsetIsTheOffset) {
  // Every channel off by 0.25: RMSE 0.25, relMSE 0.0625 / (0.5^2 + 0.01) = 0.240385.
  const ImageMetrics m =
      compare_images(filled(5, 3, 0.75f, 0.75f, 0.75f), filled(5, 3, 0.5f, 0.5f, 0.5f));
  EXPECT_NEAR(m.rmse, 0.25, 1e-7);
  EXPECT_NEAR(m.rel_mse, 0.0625 / 0.26, 1e-7);
  EXPECT_EQ(m.compared_pixels, 15u);
}

TEST(ImageMetrics, ReferenceNoiseOnTwoPixelsByHand) {
  // Reference (1, 1, 1) and (0, 0, 0) with variances 0.1 and 0.01 in every channel:
  // (0.1 / 1.01 + 0.01 / 0.01) / 2.
  ImageRGBA32F reference = filled(2, 1, 0, 0, 0), variance = filled(2, 1, 0, 0, 0);
  for (int c = 0; c < 3; ++c) {
    reference.at(0, 0)[c] = 1.0f;
    variance.at(0, 0)[c] = 0.1f;
    variance.at(1, 0)[c] = 0.01f;
  }
  EXPECT_NEAR(noise_rel_mse(reference, variance), (0.1 / 1.01 + 1.0) / 2.0, 1e-6);
  EXPECT_THROW(noise_rel_mse(reference, filled(1, 2, 0, 0, 0)), std::invalid_argument);
  EXPECT_THROW(noise_rel_mse(ImageRGBA32F(), ImageRGBA32F()), std::invalid_argument);
}

// A reference with noise of known variance around the exact image (1-3% of it: the term holds to
// first order in the relative noise): the exact image's relMSE against it is the noise term, and
// an image with an error of its own reads that error plus the noise term.
TEST(ImageMetrics, ReferenceNoiseIsWhatANoisyReferenceAddsToRelMse) {
  const uint32_t size = 192;
  ImageRGBA32F exact = filled(size, size, 0, 0, 0), noisy = exact, variance = exact;
  ImageRGBA32F biased = exact;
  std::mt19937 rng(7);
  std::normal_distribution<float> unit(0.0f, 1.0f);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      for (int c = 0; c < 3; ++c) {
        const float mean = 0.5f + float((x + 3 * y + 5 * c) % 11) / 10.0f;
        const float sigma = 0.005f + 0.005f * float((x + y) % 3);
        exact.at(x, y)[c] = mean;
        biased.at(x, y)[c] = 1.1f * mean;
        noisy.at(x, y)[c] = mean + sigma * unit(rng);
        variance.at(x, y)[c] = sigma * sigma;
      }
    }
  }
  const double noise = noise_rel_mse(noisy, variance);
  EXPECT_GT(noise, 1e-5);
  EXPECT_NEAR(compare_images(exact, noisy).rel_mse, noise, 0.03 * noise);
  const double own_error = compare_images(biased, exact).rel_mse;
  EXPECT_NEAR(compare_images(biased, noisy).rel_mse - noise, own_error, 0.03 * own_error);
}

TEST(ErrorMap, PerPixelErrorIsTheRelMseTerm) {
  ImageRGBA32F reference = filled(2, 1, 1, 1, 1), image = filled(2, 1, 1, 1, 1);
  image.at(0, 0)[0] = 1.5f;  // (0.25 / 1.01) / 3 at pixel 0, nothing at pixel 1
  const std::vector<double> errors = relative_error_per_pixel(image, reference);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_NEAR(errors[0], 0.25 / 1.01 / 3.0, 1e-9);
  EXPECT_DOUBLE_EQ(errors[1], 0.0);
  // relMSE is their mean.
  EXPECT_NEAR(compare_images(image, reference).rel_mse, (errors[0] + errors[1]) / 2.0, 1e-12);
}

TEST(ErrorMap, HeatMapRampEndsAndNonFinitePixels) {
  ImageRGBA32F reference = filled(3, 1, 1, 1, 1), image = filled(3, 1, 1, 1, 1);
  for (int c = 0; c < 3; ++c) image.at(1, 0)[c] = 10.0f;  // error 81 / 1.01, above `high`
  image.at(2, 0)[1] = std::numeric_limits<float>::quiet_NaN();
  const ImageRGBA32F map = relative_error_heat_map(image, reference, {1e-4, 1.0});
  float cold[3], hot[3];
  heat_map_colour(0.0, cold);
  heat_map_colour(1.0, hot);
  for (int c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(map.at(0, 0)[c], cold[c]) << "no error is the coldest colour";
    EXPECT_FLOAT_EQ(map.at(1, 0)[c], hot[c]) << "errors above the scale clamp to the hottest";
  }
  EXPECT_FLOAT_EQ(map.at(2, 0)[0], 1.0f);
  EXPECT_FLOAT_EQ(map.at(2, 0)[1], 0.0f);
  EXPECT_FLOAT_EQ(map.at(2, 0)[2], 1.0f) << "a NaN pixel is magenta";
}

TEST(ErrorMap, HeatMapGetsBrighterWithTheError) {
  double previous = -1.0;
  for (int i = 0; i <= 20; ++i) {
    float rgb[3];
    heat_map_colour(i / 20.0, rgb);
    const double brightness = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    EXPECT_GT(brightness, previous) << "at t = " << i / 20.0;
    previous = brightness;
  }
}

TEST(ErrorMap, BadInputIsRejected) {
  EXPECT_THROW(relative_error_per_pixel(filled(2, 2, 0, 0, 0), filled(3, 2, 0, 0, 0)),
               std::invalid_argument);
  EXPECT_THROW(relative_error_heat_map(filled(2, 2, 0, 0, 0), filled(2, 2, 0, 0, 0), {1.0, 0.5}),
               std::invalid_argument);
}

}  // namespace
}  // namespace voxgi::image
