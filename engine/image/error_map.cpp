#include "engine/image/error_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace voxgi::image {
namespace {

void check_sizes(const ImageRGBA32F& image, const ImageRGBA32F& reference) {
  if (image.width == 0 || image.height == 0) {
    throw std::invalid_argument("relative_error_per_pixel: the image is empty");
  }
  if (image.width != reference.width || image.height != reference.height) {
    throw std::invalid_argument("relative_error_per_pixel: image is " +
                                std::to_string(image.width) + "x" + std::to_string(image.height) +
                                " but the reference is " + std::to_string(reference.width) + "x" +
                                std::to_string(reference.height));
  }
}

}  // namespace

std::vector<double> relative_error_per_pixel(const ImageRGBA32F& image,
                                             const ImageRGBA32F& reference) {
  check_sizes(image, reference);
  const size_t pixels = size_t(image.width) * image.height;
  std::vector<double> errors(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const float* a = image.pixels.data() + i * 4;
    const float* b = reference.pixels.data() + i * 4;
    double sum = 0.0;
    bool finite = true;
    for (int c = 0; c < 3; ++c) {
      finite = finite && std::isfinite(a[c]) && std::isfinite(b[c]);
      const double d = double(a[c]) - double(b[c]);
      sum += d * d / (double(b[c]) * b[c] + 0.01);
    }
    errors[i] = finite ? sum / 3.0 : std::numeric_limits<double>::quiet_NaN();
  }
  return errors;
}

void heat_map_colour(double t, float rgb[3]) {
  // Control points of a perceptually ordered dark-to-bright ramp (black, purple, red-orange,
  // yellow, white-ish): brighter always means a larger error, also in greyscale print.
  static constexpr float kStops[][3] = {{0.00f, 0.00f, 0.02f},
                                        {0.32f, 0.07f, 0.43f},
                                        {0.73f, 0.21f, 0.33f},
                                        {0.98f, 0.55f, 0.04f},
                                        {0.99f, 0.99f, 0.65f}};
  constexpr int kSegments = 4;
  if (!(t > 0.0)) t = 0.0;  // also NaN
  t = std::min(t, 1.0);
  const double x = t * kSegments;
  const int i = std::min(static_cast<int>(x), kSegments - 1);
  const float f = static_cast<float>(x - i);
  for (int c = 0; c < 3; ++c) rgb[c] = kStops[i][c] + (kStops[i + 1][c] - kStops[i][c]) * f;
}

ImageRGBA32F relative_error_heat_map(const ImageRGBA32F& image, const ImageRGBA32F& reference,
                                     HeatMapScale scale) {
  if (!(scale.low > 0.0) || !(scale.high > scale.low)) {
    throw std::invalid_argument("relative_error_heat_map: the scale needs 0 < low < high");
  }
  const std::vector<double> errors = relative_error_per_pixel(image, reference);
  ImageRGBA32F map(image.width, image.height);
  const double log_low = std::log10(scale.low), log_span = std::log10(scale.high) - log_low;
  for (size_t i = 0; i < errors.size(); ++i) {
    float* out = map.pixels.data() + i * 4;
    out[3] = 1.0f;
    if (std::isnan(errors[i])) {
      out[0] = 1.0f;
      out[1] = 0.0f;
      out[2] = 1.0f;
      continue;
    }
    const double t = errors[i] <= scale.low ? 0.0 : (std::log10(errors[i]) - log_low) / log_span;
    heat_map_colour(t, out);
  }
  return map;
}

}  // namespace voxgi::image
