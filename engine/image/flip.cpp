#include "engine/image/flip.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>

namespace voxgi::image {
namespace {

constexpr double kPi = 3.14159265358979323846;

using Plane = std::vector<float>;
using Vec3 = std::array<double, 3>;

// Linear sRGB (D65) to CIE XYZ and back.
constexpr double kRgbToXyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                    {0.2126729, 0.7151522, 0.0721750},
                                    {0.0193339, 0.1191920, 0.9503041}};
constexpr double kXyzToRgb[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                    {-0.9692660, 1.8760108, 0.0415560},
                                    {0.0556434, -0.2040259, 1.0572252}};

Vec3 multiply(const double m[3][3], const Vec3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2],
          m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// The white point: XYZ of linear RGB (1, 1, 1).
const Vec3& white_xyz() {
  static const Vec3 white = multiply(kRgbToXyz, Vec3{1.0, 1.0, 1.0});
  return white;
}

// YyCxCz: L*a*b* without its cube root, linear in XYZ, so that spatial filtering in it is
// filtering of light (the colour pipeline's opponent space).
Vec3 xyz_to_ycxcz(const Vec3& xyz) {
  const Vec3& w = white_xyz();
  const double x = xyz[0] / w[0], y = xyz[1] / w[1], z = xyz[2] / w[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3 ycxcz_to_xyz(const Vec3& ycc) {
  const Vec3& w = white_xyz();
  const double y = (ycc[0] + 16.0) / 116.0;
  const double x = ycc[1] / 500.0 + y;
  const double z = y - ycc[2] / 200.0;
  return {x * w[0], y * w[1], z * w[2]};
}

Vec3 xyz_to_lab(const Vec3& xyz) {
  const Vec3& w = white_xyz();
  constexpr double kDelta = 6.0 / 29.0;
  auto f = [](double t) {
    return t > kDelta * kDelta * kDelta ? std::cbrt(t) : t / (3.0 * kDelta * kDelta) + 4.0 / 29.0;
  };
  const double fx = f(xyz[0] / w[0]), fy = f(xyz[1] / w[1]), fz = f(xyz[2] / w[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

// The Hunt effect: chroma is less visible in dark colours, so a* and b* scale with L*/100.
Vec3 hunt_adjusted_lab_of_linear_rgb(const Vec3& rgb) {
  const Vec3 lab = xyz_to_lab(multiply(kRgbToXyz, rgb));
  return {lab[0], 0.01 * lab[0] * lab[1], 0.01 * lab[0] * lab[2]};
}

// HyAB: city-block distance in lightness plus Euclidean distance in chroma, which matches
// large colour differences better than ΔE*ab.
double hyab(const Vec3& a, const Vec3& b) {
  return std::fabs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

// Separable convolution with clamped edges: `horizontal` along x, then `vertical` along y.
// Each pass adds one weighted, shifted copy of a (padded) row per tap, a loop over x that the
// compiler vectorises; HDR-FLIP runs it dozens of times per exposure on full frames.
Plane convolve(const Plane& src, uint32_t w, uint32_t h, const std::vector<double>& horizontal,
               const std::vector<double>& vertical) {
  const int rx = static_cast<int>(horizontal.size() / 2);
  const int ry = static_cast<int>(vertical.size() / 2);
  const std::vector<float> wx(horizontal.begin(), horizontal.end());
  const std::vector<float> wy(vertical.begin(), vertical.end());
  Plane rows(src.size()), result(src.size(), 0.0f);
  std::vector<float> padded(size_t(w) + 2 * size_t(rx));
  for (uint32_t y = 0; y < h; ++y) {
    const float* line = src.data() + size_t(y) * w;
    for (int i = 0; i < static_cast<int>(padded.size()); ++i) {
      padded[size_t(i)] = line[std::clamp(i - rx, 0, static_cast<int>(w) - 1)];
    }
    float* out = rows.data() + size_t(y) * w;
    std::fill(out, out + w, 0.0f);
    for (size_t tap = 0; tap < wx.size(); ++tap) {
      const float weight = wx[tap];
      const float* shifted = padded.data() + tap;
      for (uint32_t x = 0; x < w; ++x) out[x] += weight * shifted[x];
    }
  }
  for (uint32_t y = 0; y < h; ++y) {
    float* out = result.data() + size_t(y) * w;
    for (int i = -ry; i <= ry; ++i) {
      const int sy = std::clamp(static_cast<int>(y) + i, 0, static_cast<int>(h) - 1);
      const float weight = wy[size_t(i + ry)];
      const float* line = rows.data() + size_t(sy) * w;
      for (uint32_t x = 0; x < w; ++x) out[x] += weight * line[x];
    }
  }
  return result;
}

// The contrast sensitivity function of one opponent channel as a spatial kernel: a sum of
// two Gaussians a·sqrt(π/b)·exp(−π²r²/b) (r in degrees), normalised to sum to 1. Each term is
// separable, so the kernel is applied as two separable convolutions.
struct CsfChannel {
  double a1, b1, a2, b2;
};
constexpr CsfChannel kCsfAchromatic{1.0, 0.0047, 0.0, 1e-5};
constexpr CsfChannel kCsfRedGreen{1.0, 0.0053, 0.0, 1e-5};
constexpr CsfChannel kCsfBlueYellow{34.1, 0.04, 13.5, 0.025};

// One radius for all three channels, from the widest Gaussian (3 standard deviations).
int csf_radius(double ppd) {
  const double widest = 0.04;
  return static_cast<int>(std::ceil(3.0 * std::sqrt(widest / (2.0 * kPi * kPi)) * ppd));
}

Plane csf_filter(const Plane& src, uint32_t w, uint32_t h, const CsfChannel& csf, double ppd) {
  const int radius = csf_radius(ppd);
  auto gaussian = [&](double b) {
    std::vector<double> g(size_t(2 * radius + 1));
    for (int i = -radius; i <= radius; ++i) {
      const double degrees = i / ppd;
      g[size_t(i + radius)] = std::exp(-kPi * kPi * degrees * degrees / b);
    }
    return g;
  };
  auto sum_of = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s;
  };
  const std::vector<double> g1 = gaussian(csf.b1), g2 = gaussian(csf.b2);
  const double w1 = csf.a1 * std::sqrt(kPi / csf.b1);
  const double w2 = csf.a2 * std::sqrt(kPi / csf.b2);
  const double total = w1 * sum_of(g1) * sum_of(g1) + w2 * sum_of(g2) * sum_of(g2);
  std::vector<double> scaled1 = g1;
  for (double& x : scaled1) x *= w1 / total;
  Plane result = convolve(src, w, h, scaled1, g1);
  if (csf.a2 != 0.0) {
    std::vector<double> scaled2 = g2;
    for (double& x : scaled2) x *= w2 / total;
    const Plane second = convolve(src, w, h, scaled2, g2);
    for (size_t i = 0; i < result.size(); ++i) result[i] += second[i];
  }
  return result;
}

// Edge (first derivative of a Gaussian) and point (second derivative) detectors along x, as
// separable kernels: the derivative along x times the Gaussian along y. The 2D kernel's
// positive weights sum to 1 and its negative weights to −1, so a step of height 1 gives an
// edge response of 1; both signs depend only on x, so the 1D derivative factor is normalised
// that way and the Gaussian factor to sum 1. The Gaussian's standard deviation is half the
// peak-to-trough width (0.082°) of the human edge detector.
struct FeatureKernels {
  std::vector<double> edge, point, gaussian;
};

FeatureKernels feature_kernels(double ppd) {
  const double sigma = 0.5 * 0.082 * ppd;
  const int radius = static_cast<int>(std::ceil(3.0 * sigma));
  FeatureKernels k;
  double gaussian_sum = 0.0;
  for (int i = -radius; i <= radius; ++i) {
    const double g = std::exp(-(i * i) / (2.0 * sigma * sigma));
    k.gaussian.push_back(g);
    k.edge.push_back(-i * g);
    k.point.push_back((i * i / (sigma * sigma) - 1.0) * g);
    gaussian_sum += g;
  }
  for (double& g : k.gaussian) g /= gaussian_sum;
  for (std::vector<double>* derivative : {&k.edge, &k.point}) {
    double positive = 0.0, negative = 0.0;
    for (double v : *derivative) (v > 0.0 ? positive : negative) += v;
    for (double& v : *derivative) v = v > 0.0 ? v / positive : v / -negative;
  }
  return k;
}

// Edge and point strengths (gradient magnitudes of the two detectors) of relative luminance.
struct Features {
  Plane edge, point;
};

Features features_of(const Plane& luminance, uint32_t w, uint32_t h, const FeatureKernels& k) {
  const Plane edge_x = convolve(luminance, w, h, k.edge, k.gaussian);
  const Plane edge_y = convolve(luminance, w, h, k.gaussian, k.edge);
  const Plane point_x = convolve(luminance, w, h, k.point, k.gaussian);
  const Plane point_y = convolve(luminance, w, h, k.gaussian, k.point);
  Features f;
  f.edge.resize(luminance.size());
  f.point.resize(luminance.size());
  for (size_t i = 0; i < luminance.size(); ++i) {
    f.edge[i] = std::hypot(edge_x[i], edge_y[i]);
    f.point[i] = std::hypot(point_x[i], point_y[i]);
  }
  return f;
}

// An image in YyCxCz, one plane per channel, from linear RGB clamped to [0, 1].
struct Opponent {
  std::array<Plane, 3> channel;
};

Opponent opponent_of(const std::vector<Vec3>& rgb) {
  Opponent o;
  for (Plane& p : o.channel) p.resize(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) {
    const Vec3 ycc = xyz_to_ycxcz(multiply(kRgbToXyz, rgb[i]));
    for (int c = 0; c < 3; ++c) o.channel[size_t(c)][i] = static_cast<float>(ycc[size_t(c)]);
  }
  return o;
}

// Perceived colours: the opponent channels filtered by their CSFs, back in linear RGB clamped
// to the displayable cube, in Hunt-adjusted L*a*b*.
std::vector<Vec3> perceived_lab(const Opponent& o, uint32_t w, uint32_t h, double ppd) {
  const Plane y = csf_filter(o.channel[0], w, h, kCsfAchromatic, ppd);
  const Plane cx = csf_filter(o.channel[1], w, h, kCsfRedGreen, ppd);
  const Plane cz = csf_filter(o.channel[2], w, h, kCsfBlueYellow, ppd);
  std::vector<Vec3> lab(y.size());
  for (size_t i = 0; i < y.size(); ++i) {
    Vec3 rgb = multiply(kXyzToRgb, ycxcz_to_xyz({y[i], cx[i], cz[i]}));
    for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
    lab[i] = hunt_adjusted_lab_of_linear_rgb(rgb);
  }
  return lab;
}

// LDR-FLIP of two images of linear RGB in [0, 1].
std::vector<float> ldr_flip_of(const std::vector<Vec3>& test, const std::vector<Vec3>& reference,
                               uint32_t w, uint32_t h, double ppd, const FeatureKernels& kernels) {
  constexpr double kColorExponent = 0.7;    // q_c
  constexpr double kFeatureExponent = 0.5;  // q_f
  // Colour differences below p_c · c_max take the lower p_t of the error range.
  constexpr double kColorKnee = 0.4;   // p_c
  constexpr double kErrorKnee = 0.95;  // p_t
  static const double c_max = std::pow(hyab(hunt_adjusted_lab_of_linear_rgb({0.0, 1.0, 0.0}),
                                            hunt_adjusted_lab_of_linear_rgb({0.0, 0.0, 1.0})),
                                       kColorExponent);

  const Opponent test_opponent = opponent_of(test), reference_opponent = opponent_of(reference);
  const std::vector<Vec3> test_lab = perceived_lab(test_opponent, w, h, ppd);
  const std::vector<Vec3> reference_lab = perceived_lab(reference_opponent, w, h, ppd);

  // Features of the relative luminance Y/Y_white = (y + 16) / 116, in [0, 1].
  auto relative_luminance = [](const Opponent& o) {
    Plane y(o.channel[0].size());
    for (size_t i = 0; i < y.size(); ++i) y[i] = (o.channel[0][i] + 16.0f) / 116.0f;
    return y;
  };
  const Features test_features = features_of(relative_luminance(test_opponent), w, h, kernels);
  const Features reference_features =
      features_of(relative_luminance(reference_opponent), w, h, kernels);

  std::vector<float> error(test.size());
  for (size_t i = 0; i < test.size(); ++i) {
    const double color = std::pow(hyab(test_lab[i], reference_lab[i]), kColorExponent);
    const double knee = kColorKnee * c_max;
    const double color_error =
        color < knee ? kErrorKnee / knee * color
                     : kErrorKnee + (color - knee) / (c_max - knee) * (1.0 - kErrorKnee);
    const double feature_difference =
        std::max(std::fabs(test_features.edge[i] - reference_features.edge[i]),
                 std::fabs(test_features.point[i] - reference_features.point[i]));
    const double feature_error =
        std::clamp(std::pow(feature_difference / std::sqrt(2.0), kFeatureExponent), 0.0, 1.0);
    // Features sharpen the colour error: a difference at an edge or point is more visible.
    error[i] = static_cast<float>(std::pow(color_error, 1.0 - feature_error));
  }
  return error;
}

void check_sizes(const ImageRGBA32F& test, const ImageRGBA32F& reference, const char* what) {
  if (test.width == 0 || test.height == 0) {
    throw std::invalid_argument(std::string(what) + ": the image is empty");
  }
  if (test.width != reference.width || test.height != reference.height) {
    throw std::invalid_argument(std::string(what) + ": image is " + std::to_string(test.width) +
                                "x" + std::to_string(test.height) + " but the reference is " +
                                std::to_string(reference.width) + "x" +
                                std::to_string(reference.height));
  }
}

double finite_or_zero(float v) {
  return std::isfinite(v) ? std::max(double(v), 0.0) : 0.0;
}

double mean_of(const std::vector<float>& v) {
  double sum = 0.0;
  for (float x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

constexpr double kAces[6] = {0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14};

// The input x > 0 the tone mapper maps to `target` in (0, 1): the positive root of
// (k0 − t·k3)x² + (k1 − t·k4)x + (k2 − t·k5) = 0.
double tone_map_inverse(double target) {
  const double a = kAces[0] - target * kAces[3];
  const double b = kAces[1] - target * kAces[4];
  const double c = kAces[2] - target * kAces[5];
  return (-b + std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
}

}  // namespace

double flip_tone_map(double x) {
  return (kAces[0] * x * x + kAces[1] * x + kAces[2]) /
         (kAces[3] * x * x + kAces[4] * x + kAces[5]);
}

FlipResult ldr_flip(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                    const FlipOptions& options) {
  check_sizes(test, reference, "ldr_flip");
  const size_t n = size_t(test.width) * test.height;
  std::vector<Vec3> a(n), b(n);
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      a[i][size_t(c)] = std::min(finite_or_zero(test.pixels[i * 4 + size_t(c)]), 1.0);
      b[i][size_t(c)] = std::min(finite_or_zero(reference.pixels[i * 4 + size_t(c)]), 1.0);
    }
  }
  FlipResult result;
  result.error = ldr_flip_of(a, b, test.width, test.height, options.pixels_per_degree,
                             feature_kernels(options.pixels_per_degree));
  result.mean = mean_of(result.error);
  return result;
}

HdrFlipResult hdr_flip(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                       const FlipOptions& options) {
  check_sizes(test, reference, "hdr_flip");
  const size_t n = size_t(test.width) * test.height;
  std::vector<Vec3> a(n), b(n);
  std::vector<double> luminance(n);
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      a[i][size_t(c)] = finite_or_zero(test.pixels[i * 4 + size_t(c)]);
      b[i][size_t(c)] = finite_or_zero(reference.pixels[i * 4 + size_t(c)]);
    }
    luminance[i] = 0.2126 * b[i][0] + 0.7152 * b[i][1] + 0.0722 * b[i][2];
  }

  // The brightest reference pixel reaches 0.85 after tone mapping at the first exposure, the
  // median one at the last; a black median (a mostly black view) falls back to the median of
  // the lit pixels, and a black reference to a single exposure range around 0 stops.
  HdrFlipResult result;
  const double y_max = *std::max_element(luminance.begin(), luminance.end());
  std::vector<double> sorted = luminance;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(n / 2), sorted.end());
  double y_median = sorted[n / 2];
  if (y_median <= 0.0) {
    std::vector<double> lit;
    for (double y : luminance) {
      if (y > 0.0) lit.push_back(y);
    }
    if (!lit.empty()) {
      std::nth_element(lit.begin(), lit.begin() + static_cast<long>(lit.size() / 2), lit.end());
      y_median = lit[lit.size() / 2];
    }
  }
  const double x_085 = tone_map_inverse(0.85);
  if (y_max > 0.0 && y_median > 0.0) {
    result.start_exposure = std::log2(x_085 / y_max);
    result.stop_exposure = std::log2(x_085 / y_median);
  }
  result.exposures =
      static_cast<uint32_t>(std::max(2.0, std::ceil(result.stop_exposure - result.start_exposure)));
  const double step =
      (result.stop_exposure - result.start_exposure) / static_cast<double>(result.exposures - 1);

  // Exposures are independent: each worker thread takes every k-th one and keeps its own
  // per-pixel maximum (a full-HD frame costs about half a second per exposure on one core).
  const FeatureKernels kernels = feature_kernels(options.pixels_per_degree);
  const uint32_t workers =
      std::clamp(std::thread::hardware_concurrency(), 1u, std::min(result.exposures, 8u));
  std::vector<std::vector<float>> maxima(workers, std::vector<float>(n, 0.0f));
  const auto work = [&](uint32_t worker) {
    std::vector<Vec3> a_ldr(n), b_ldr(n);
    for (uint32_t e = worker; e < result.exposures; e += workers) {
      const double scale = std::exp2(result.start_exposure + step * e);
      for (size_t i = 0; i < n; ++i) {
        for (size_t c = 0; c < 3; ++c) {
          a_ldr[i][c] = std::clamp(flip_tone_map(scale * a[i][c]), 0.0, 1.0);
          b_ldr[i][c] = std::clamp(flip_tone_map(scale * b[i][c]), 0.0, 1.0);
        }
      }
      const std::vector<float> error =
          ldr_flip_of(a_ldr, b_ldr, test.width, test.height, options.pixels_per_degree, kernels);
      std::vector<float>& maximum = maxima[worker];
      for (size_t i = 0; i < n; ++i) maximum[i] = std::max(maximum[i], error[i]);
    }
  };
  std::vector<std::thread> threads;
  for (uint32_t worker = 1; worker < workers; ++worker) threads.emplace_back(work, worker);
  work(0);
  for (std::thread& thread : threads) thread.join();
  result.error = std::move(maxima[0]);
  for (uint32_t worker = 1; worker < workers; ++worker) {
    for (size_t i = 0; i < n; ++i) result.error[i] = std::max(result.error[i], maxima[worker][i]);
  }
  result.mean = mean_of(result.error);
  return result;
}

}  // namespace voxgi::image
