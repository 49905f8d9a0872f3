#include "engine/image/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "engine/image/flip.hpp"

namespace voxgi::image {
namespace {

bool finite_pixel(const float* p) {
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Throws std::invalid_argument, naming `function`, when `image` is empty or its size differs
// from the reference's.
void require_same_size(const char* function, const char* what, const ImageRGBA32F& image,
                       const ImageRGBA32F& reference) {
  if (image.width == 0 || image.height == 0) {
    throw std::invalid_argument(std::string(function) + ": " + what + " is empty");
  }
  if (image.width != reference.width || image.height != reference.height) {
    throw std::invalid_argument(std::string(function) + ": " + what + " is " +
                                std::to_string(image.width) + "x" + std::to_string(image.height) +
                                " but the reference is " + std::to_string(reference.width) + "x" +
                                std::to_string(reference.height));
  }
}

// Separable Gaussian blur of a single-channel image with clamped edges; the SSIM window.
std::vector<double> gaussian_blur(const std::vector<double>& src, uint32_t w, uint32_t h) {
  constexpr int kRadius = 5;
  constexpr double kSigma = 1.5;
  double weights[2 * kRadius + 1];
  double total = 0.0;
  for (int i = -kRadius; i <= kRadius; ++i) {
    weights[i + kRadius] = std::exp(-0.5 * i * i / (kSigma * kSigma));
    total += weights[i + kRadius];
  }
  for (double& weight : weights) weight /= total;
  auto clamp_index = [](int v, uint32_t n) {
    return static_cast<size_t>(std::min(std::max(v, 0), static_cast<int>(n) - 1));
  };
  std::vector<double> horizontal(src.size()), result(src.size());
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int i = -kRadius; i <= kRadius; ++i) {
        sum += weights[i + kRadius] * src[size_t(y) * w + clamp_index(int(x) + i, w)];
      }
      horizontal[size_t(y) * w + x] = sum;
    }
  }
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      double sum = 0.0;
      for (int i = -kRadius; i <= kRadius; ++i) {
        sum += weights[i + kRadius] * horizontal[clamp_index(int(y) + i, h) * w + x];
      }
      result[size_t(y) * w + x] = sum;
    }
  }
  return result;
}

double ssim_of(const std::vector<double>& a, const std::vector<double>& b, uint32_t w, uint32_t h) {
  constexpr double kC1 = 0.01 * 0.01;
  constexpr double kC2 = 0.03 * 0.03;
  std::vector<double> aa(a.size()), bb(a.size()), ab(a.size());
  for (size_t i = 0; i < a.size(); ++i) {
    aa[i] = a[i] * a[i];
    bb[i] = b[i] * b[i];
    ab[i] = a[i] * b[i];
  }
  const std::vector<double> mu_a = gaussian_blur(a, w, h), mu_b = gaussian_blur(b, w, h);
  const std::vector<double> e_aa = gaussian_blur(aa, w, h), e_bb = gaussian_blur(bb, w, h),
                            e_ab = gaussian_blur(ab, w, h);
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double var_a = e_aa[i] - mu_a[i] * mu_a[i];
    const double var_b = e_bb[i] - mu_b[i] * mu_b[i];
    const double cov = e_ab[i] - mu_a[i] * mu_b[i];
    sum += ((2.0 * mu_a[i] * mu_b[i] + kC1) * (2.0 * cov + kC2)) /
           ((mu_a[i] * mu_a[i] + mu_b[i] * mu_b[i] + kC1) * (var_a + var_b + kC2));
  }
  return sum / static_cast<double>(a.size());
}

}  // namespace

double luminance(const float* rgba) {
  return 0.2126 * rgba[0] + 0.7152 * rgba[1] + 0.0722 * rgba[2];
}

double mean_luminance(const ImageRGBA32F& image) {
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i + 3 < image.pixels.size(); i += 4) {
    const float* p = image.pixels.data() + i;
    if (!finite_pixel(p)) continue;
    sum += luminance(p);
    ++count;
  }
  return count ? sum / static_cast<double>(count) : 0.0;
}

ImageMetrics compare_images(const ImageRGBA32F& image, const ImageRGBA32F& reference) {
  require_same_size("compare_images", "the image", image, reference);
  ImageMetrics m;
  const size_t pixels = size_t(image.width) * image.height;
  // Non-finite pixels enter SSIM as black in both images so the windows stay aligned.
  std::vector<double> lum_a(pixels, 0.0), lum_b(pixels, 0.0);
  double squared = 0.0, relative = 0.0, sum_a = 0.0, sum_b = 0.0;
  for (size_t i = 0; i < pixels; ++i) {
    const float* a = image.pixels.data() + i * 4;
    const float* b = reference.pixels.data() + i * 4;
    const bool a_ok = finite_pixel(a), b_ok = finite_pixel(b);
    if (!a_ok) ++m.non_finite_pixels;
    if (!b_ok) ++m.non_finite_reference_pixels;
    if (!a_ok || !b_ok) continue;
    ++m.compared_pixels;
    for (int c = 0; c < 3; ++c) {
      const double d = double(a[c]) - double(b[c]);
      squared += d * d;
      relative += d * d / (double(b[c]) * b[c] + 0.01);
    }
    const double ya = luminance(a), yb = luminance(b);
    sum_a += ya;
    sum_b += yb;
    lum_a[i] = std::max(ya, 0.0) / (1.0 + std::max(ya, 0.0));
    lum_b[i] = std::max(yb, 0.0) / (1.0 + std::max(yb, 0.0));
  }
  if (m.compared_pixels > 0) {
    const double n = static_cast<double>(m.compared_pixels);
    m.rmse = std::sqrt(squared / (3.0 * n));
    m.rel_mse = relative / (3.0 * n);
    m.mean_luminance = sum_a / n;
    m.mean_luminance_reference = sum_b / n;
    m.luminance_bias =
        m.mean_luminance_reference > 0.0
            ? (m.mean_luminance - m.mean_luminance_reference) / m.mean_luminance_reference
            : 0.0;
  }
  m.ssim_luminance = ssim_of(lum_a, lum_b, image.width, image.height);
  m.hdr_flip = hdr_flip(image, reference).mean;
  return m;
}

double noise_rel_mse(const ImageRGBA32F& reference, const ImageRGBA32F& variance_of_mean) {
  require_same_size("noise_rel_mse", "the variance", variance_of_mean, reference);
  const size_t pixels = size_t(reference.width) * reference.height;
  double sum = 0.0;
  size_t counted = 0;
  for (size_t i = 0; i < pixels; ++i) {
    const float* b = reference.pixels.data() + i * 4;
    const float* v = variance_of_mean.pixels.data() + i * 4;
    if (!finite_pixel(b) || !finite_pixel(v)) continue;
    ++counted;
    for (int c = 0; c < 3; ++c) sum += std::max(double(v[c]), 0.0) / (double(b[c]) * b[c] + 0.01);
  }
  return counted > 0 ? sum / (3.0 * double(counted)) : 0.0;
}

}  // namespace voxgi::image
