// LDR- and HDR-FLIP: properties that follow from the definition (identical images, the
// largest colour difference, symmetry, exposure invariance) on small synthetic images.

#include "engine/image/flip.hpp"
#include "tests/image/filled_image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace voxgi::image {
namespace {

// A lit room-like HDR image: a smooth gradient with a bright square and a checker, so that
// colour, edges and points all differ between the variants below. `shift` moves the pattern.
ImageRGBA32F pattern(uint32_t size, int shift, float brightness) {
  ImageRGBA32F image(size, size);
  for (uint32_t y = 0; y < size; ++y) {
    for (uint32_t x = 0; x < size; ++x) {
      const int sx = static_cast<int>(x) + shift;
      float* p = image.at(x, y);
      const float ramp = 0.05f + 0.5f * static_cast<float>(y) / static_cast<float>(size);
      const bool checker = ((sx / 4) + static_cast<int>(y / 4)) % 2 == 0;
      const bool lamp = sx > 40 && sx < 52 && y > 8 && y < 20;
      p[0] = brightness * (ramp + (checker ? 0.3f : 0.0f) + (lamp ? 20.0f : 0.0f));
      p[1] = brightness * (0.8f * ramp + (lamp ? 18.0f : 0.0f));
      p[2] = brightness * (0.6f * ramp + (checker ? 0.0f : 0.2f));
      p[3] = 1.0f;
    }
  }
  return image;
}

TEST(Flip, IdenticalImagesHaveNoError) {
  const ImageRGBA32F ldr = filled(32, 32, 0.3f, 0.6f, 0.9f);
  EXPECT_EQ(ldr_flip(ldr, ldr).mean, 0.0);
  const ImageRGBA32F hdr = pattern(64, 0, 1.0f);
  const HdrFlipResult result = hdr_flip(hdr, hdr);
  EXPECT_EQ(result.mean, 0.0);
  for (float e : result.error) EXPECT_EQ(e, 0.0f);
}

TEST(Flip, GreenAgainstBlueIsTheLargestError) {
  // The colour error is normalised by the HyAB distance of pure green and pure blue, and flat
  // images have no features, so every pixel is exactly 1.
  const FlipResult result = ldr_flip(filled(16, 16, 0, 1, 0), filled(16, 16, 0, 0, 1));
  EXPECT_NEAR(result.mean, 1.0, 1e-6);
}

TEST(Flip, BlackAgainstWhiteIsInTheUpperErrorRange) {
  // HyAB(black, white)^0.7 = 100^0.7 ≈ 25.1 lies above the knee p_c · c_max ≈ 16.5, so the
  // error lies between p_t = 0.95 and 1.
  const double error = ldr_flip(filled(16, 16, 0, 0, 0), filled(16, 16, 1, 1, 1)).mean;
  EXPECT_GT(error, 0.95);
  EXPECT_LT(error, 1.0);
}

TEST(Flip, GrowsWithTheDifference) {
  const ImageRGBA32F reference = filled(16, 16, 0.5f, 0.5f, 0.5f);
  double previous = 0.0;
  for (float value : {0.52f, 0.55f, 0.6f, 0.7f, 0.9f}) {
    const double error = ldr_flip(filled(16, 16, value, value, value), reference).mean;
    EXPECT_GT(error, previous) << value;
    previous = error;
  }
}

TEST(Flip, LdrFlipIsSymmetric) {
  const ImageRGBA32F a = pattern(64, 0, 0.04f), b = pattern(64, 3, 0.03f);
  const FlipResult ab = ldr_flip(a, b), ba = ldr_flip(b, a);
  ASSERT_GT(ab.mean, 0.0);
  EXPECT_NEAR(ab.mean, ba.mean, 1e-7);
  for (size_t i = 0; i < ab.error.size(); ++i) EXPECT_NEAR(ab.error[i], ba.error[i], 1e-6);
}

TEST(Flip, HdrFlipIsSymmetricWhenTheExposureRangesAgree) {
  // The exposure range comes from the reference; a shifted copy has the same largest and
  // median luminance (the pattern repeats), so swapping the roles changes nothing.
  const ImageRGBA32F a = pattern(64, 0, 1.0f), b = pattern(64, 8, 1.0f);
  const HdrFlipResult ab = hdr_flip(a, b), ba = hdr_flip(b, a);
  ASSERT_GT(ab.mean, 0.0);
  EXPECT_DOUBLE_EQ(ab.start_exposure, ba.start_exposure);
  EXPECT_NEAR(ab.mean, ba.mean, 1e-7);
}

TEST(Flip, HdrFlipDoesNotDependOnTheOverallExposure) {
  // Scaling both images by 2^k moves the exposure range by −k stops and leaves every
  // tone-mapped image as it was.
  const HdrFlipResult base = hdr_flip(pattern(64, 2, 1.0f), pattern(64, 0, 1.2f));
  const HdrFlipResult scaled = hdr_flip(pattern(64, 2, 8.0f), pattern(64, 0, 9.6f));
  EXPECT_NEAR(scaled.start_exposure, base.start_exposure - 3.0, 1e-5);
  EXPECT_NEAR(scaled.mean, base.mean, 1e-5);
  EXPECT_GE(base.exposures, 2u);
}

TEST(Flip, HdrExposureRangeFollowsTheReference) {
  // Brightest pixel 16, median 1: the range spans log2(16) = 4 stops, starting where 16 maps
  // to 0.85.
  ImageRGBA32F reference = filled(8, 8, 1, 1, 1);
  float* bright = reference.at(3, 3);
  bright[0] = bright[1] = bright[2] = 16.0f;
  const HdrFlipResult result = hdr_flip(reference, reference);
  EXPECT_NEAR(result.stop_exposure - result.start_exposure, 4.0, 1e-9);
  EXPECT_EQ(result.exposures, 4u);
  EXPECT_NEAR(flip_tone_map(std::exp2(result.start_exposure) * 16.0), 0.85, 1e-9);
}

TEST(Flip, TooBrightIsWorseThanSlightlyBright) {
  const ImageRGBA32F reference = pattern(64, 0, 1.0f);
  const double slight = hdr_flip(pattern(64, 0, 1.1f), reference).mean;
  const double strong = hdr_flip(pattern(64, 0, 2.0f), reference).mean;
  EXPECT_GT(slight, 0.0);
  EXPECT_GT(strong, slight);
  EXPECT_LE(strong, 1.0);
}

TEST(Flip, NonFinitePixelsCountAsBlackAndBlackReferencesWork) {
  ImageRGBA32F test = filled(16, 16, 0.5f, 0.5f, 0.5f);
  test.at(4, 4)[0] = std::numeric_limits<float>::quiet_NaN();
  test.at(5, 5)[1] = std::numeric_limits<float>::infinity();
  const HdrFlipResult result = hdr_flip(test, filled(16, 16, 0.5f, 0.5f, 0.5f));
  EXPECT_TRUE(std::isfinite(result.mean));
  EXPECT_GT(result.mean, 0.0);
  const HdrFlipResult black = hdr_flip(test, filled(16, 16, 0, 0, 0));
  EXPECT_TRUE(std::isfinite(black.mean));
  EXPECT_GT(black.mean, 0.0);
}

TEST(Flip, AgreesWithThePublishedImplementation) {
  // Means the authors' FLIP tool (v1.6, default viewing conditions, ACES) printed for these
  // pairs written as 32-bit EXR files: the pattern shifted by 3 pixels, and 30% brighter.
  const ImageRGBA32F reference = pattern(128, 0, 1.0f);
  EXPECT_NEAR(hdr_flip(pattern(128, 3, 1.0f), reference).mean, 0.152512, 5e-5);
  const HdrFlipResult brighter = hdr_flip(pattern(128, 0, 1.3f), reference);
  EXPECT_NEAR(brighter.mean, 0.267037, 5e-5);
  // The tool's exposure range for this reference: -3.0288 to 2.8754 in 6 exposures.
  EXPECT_NEAR(brighter.start_exposure, -3.0288, 5e-5);
  EXPECT_NEAR(brighter.stop_exposure, 2.8754, 5e-5);
  EXPECT_EQ(brighter.exposures, 6u);
}

TEST(Flip, MismatchedSizesThrow) {
  EXPECT_THROW(hdr_flip(filled(8, 8, 0, 0, 0), filled(8, 9, 0, 0, 0)), std::invalid_argument);
  EXPECT_THROW(ldr_flip(ImageRGBA32F(), ImageRGBA32F()), std::invalid_argument);
}

}  // namespace
}  // namespace voxgi::image
