#pragma once
// Error metrics of a rendered image against a reference, for "what accuracy costs".
// Pixels where either image is NaN or Inf are left out of every error and counted instead, so
// one bad pixel shows up as a count rather than as a NaN metric.

#include <cstddef>
#include <stdexcept>

#include "engine/image/image.hpp"

namespace voxgi::image {

struct ImageMetrics {
  // mean over pixels and RGB channels of (a - b)^2 / (b^2 + 0.01), as the offline references
  // define it (shared/references/README.md)
  double rel_mse = 0.0;
  double rmse = 0.0;  // over pixels and RGB channels
  // Mean SSIM of luminance (Rec. 709 weights) compressed by y / (1 + y) into [0, 1), so that
  // HDR values have a fixed dynamic range; 11×11 Gaussian windows (σ = 1.5), C1 = 0.01²,
  // C2 = 0.03². 1 = structurally identical.
  double ssim_luminance = 1.0;
  // Mean HDR-FLIP (engine/image/flip.hpp): perceived difference after tone mapping over the
  // reference's exposure range, per pixel in [0, 1], 0 = indistinguishable. Non-finite
  // components enter it as 0.
  double hdr_flip = 0.0;
  double mean_luminance = 0.0;            // of the image under test
  double mean_luminance_reference = 0.0;  // of the reference
  // (mean_luminance - mean_luminance_reference) / mean_luminance_reference: negative when
  // the image is too dark, positive when too bright; 0 when the reference is black.
  double luminance_bias = 0.0;
  size_t non_finite_pixels = 0;            // in the image under test
  size_t non_finite_reference_pixels = 0;  // in the reference
  size_t compared_pixels = 0;
};

// Throws std::invalid_argument when the sizes differ or an image is empty.
ImageMetrics compare_images(const ImageRGBA32F& image, const ImageRGBA32F& reference);

// The relMSE that noise adds in expectation, in either image, to that of images whose errors do
// not follow it: the mean over pixels and RGB channels of variance / (b^2 + 0.01), b the
// reference and `variance_of_mean` the variance of the noisy image's per-pixel estimate (a path
// tracer's, from its samples). A render of n samples per pixel against a converged reference,
// or any image against a reference of n samples, reads (to first order in the relative noise)
// its error against the converged image plus this, which falls as 1/n. Pixels where either
// image is not finite are left out, as in compare_images. Throws std::invalid_argument when the
// sizes differ or an image is empty.
double noise_rel_mse(const ImageRGBA32F& reference, const ImageRGBA32F& variance_of_mean);

double luminance(const float* rgba);
// Mean luminance over the pixels whose RGB are finite; 0 for an empty image.
double mean_luminance(const ImageRGBA32F& image);

}  // namespace voxgi::image
