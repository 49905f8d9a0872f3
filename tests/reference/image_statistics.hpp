#pragma once
// Statistics of path-traced images that use the tracer's own per-pixel variance estimate, and
// the reference images of ../shared/references brought to the test resolution.

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "engine/image/image.hpp"
#include "tests/common/render_harness.hpp"

namespace voxgi::test {

struct MeanEstimate {
  double value = 0.0;                   // mean over pixels of one channel
  double standard_error = 0.0;          // of that mean, from the per-pixel variances of the mean
  double pixel_spread_variance = 0.0;   // sample variance of the pixel values
  double mean_variance_estimate = 0.0;  // mean of the per-pixel variance estimates
};

inline MeanEstimate image_mean(const RenderedImage& image, const RenderedImage& variance, int ch) {
  MeanEstimate m;
  const size_t n = static_cast<size_t>(image.width) * image.height;
  double sum = 0.0, sum_sq = 0.0, var_sum = 0.0;
  for (size_t i = 0; i < n; ++i) {
    const double v = image.rgba[i * 4 + ch];
    sum += v;
    sum_sq += v * v;
    var_sum += variance.rgba[i * 4 + ch];
  }
  m.value = sum / n;
  m.pixel_spread_variance = (sum_sq / n - m.value * m.value) * n / (n - 1.0);
  m.mean_variance_estimate = var_sum / n;
  m.standard_error = std::sqrt(var_sum) / n;
  return m;
}

inline image::ImageRGBA32F to_image(const RenderedImage& r) {
  image::ImageRGBA32F out(r.width, r.height);
  out.pixels = r.rgba;
  return out;
}

// Averages factor × factor blocks: a 1-pixel box filter image at factor times the resolution
// becomes the 1-pixel box filter image at this resolution (pixel footprints coincide).
inline image::ImageRGBA32F box_downsample(const image::ImageRGBA32F& in, uint32_t factor) {
  if (factor == 0 || in.width % factor != 0 || in.height % factor != 0) {
    throw std::invalid_argument("box_downsample: size not divisible by the factor");
  }
  image::ImageRGBA32F out(in.width / factor, in.height / factor);
  const float scale = 1.0f / static_cast<float>(factor * factor);
  for (uint32_t y = 0; y < out.height; ++y) {
    for (uint32_t x = 0; x < out.width; ++x) {
      float* o = out.at(x, y);
      for (uint32_t dy = 0; dy < factor; ++dy) {
        for (uint32_t dx = 0; dx < factor; ++dx) {
          const float* p = in.at(x * factor + dx, y * factor + dy);
          for (int c = 0; c < 4; ++c) o[c] += p[c] * scale;
        }
      }
    }
  }
  return out;
}

// Standard error of the mean luminance (Rec. 709) of a render, bounding each pixel's
// luminance variance by (sum_c w_c sigma_c)^2 since the channels are correlated.
inline double mean_luminance_standard_error(const RenderedImage& variance) {
  const double w[3] = {0.2126, 0.7152, 0.0722};
  double var_sum = 0.0;
  const size_t n = static_cast<size_t>(variance.width) * variance.height;
  for (size_t i = 0; i < n; ++i) {
    double sigma = 0.0;
    for (int c = 0; c < 3; ++c) sigma += w[c] * std::sqrt(std::max(0.0f, variance.rgba[i * 4 + c]));
    var_sum += sigma * sigma;
  }
  return std::sqrt(var_sum) / n;
}

}  // namespace voxgi::test
