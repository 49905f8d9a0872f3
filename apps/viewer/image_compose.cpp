#include "apps/viewer/image_compose.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace voxgi::viewer {
namespace {

float srgb_encode(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

image::ImageRGBA32F wipe(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b, float split) {
  if (a.width != b.width || a.height != b.height) {
    throw std::invalid_argument("wipe: the two graphs' images differ in size (" +
                                std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                                std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  }
  image::ImageRGBA32F out = a;
  const uint32_t first_b = static_cast<uint32_t>(
      std::lround(std::clamp(split, 0.0f, 1.0f) * static_cast<float>(a.width)));
  for (uint32_t y = 0; y < a.height; ++y) {
    for (uint32_t x = first_b; x < a.width; ++x) std::copy_n(b.at(x, y), 4, out.at(x, y));
  }
  return out;
}

image::ImageRGBA32F inspect_to_display(const image::ImageRGBA32F& values, float exposure_ev,
                                       bool display_referred, Channels channels) {
  image::ImageRGBA32F out(values.width, values.height);
  const float scale = std::exp2(exposure_ev);
  for (size_t i = 0; i < values.pixels.size(); i += 4) {
    const float* in = &values.pixels[i];
    float rgb[3] = {in[0], in[1], in[2]};
    switch (channels) {
      case Channels::RGB:
        break;
      case Channels::R:
      case Channels::G:
      case Channels::B:
      case Channels::A: {
        const float v = in[static_cast<int>(channels) - 1];
        rgb[0] = rgb[1] = rgb[2] = v;
        break;
      }
    }
    float* o = &out.pixels[i];
    o[3] = 1.0f;
    bool bad = false, negative = false;
    for (float v : rgb) {
      bad = bad || !std::isfinite(v);
      negative = negative || v < 0.0f;
    }
    if (bad || negative) {
      o[0] = bad ? 1.0f : 0.0f;
      o[1] = bad ? 0.0f : 1.0f;
      o[2] = 1.0f;
      continue;
    }
    for (int c = 0; c < 3; ++c) {
      const float v = rgb[c] * scale;
      o[c] = display_referred ? std::clamp(v, 0.0f, 1.0f) : srgb_encode(v);
    }
  }
  return out;
}

image::ImageRGBA32F fit_nearest(const image::ImageRGBA32F& source, uint32_t width,
                                uint32_t height) {
  image::ImageRGBA32F out(width, height);
  for (size_t i = 3; i < out.pixels.size(); i += 4) out.pixels[i] = 1.0f;
  if (source.width == 0 || source.height == 0) return out;
  const double scale = std::min(static_cast<double>(width) / source.width,
                                static_cast<double>(height) / source.height);
  const auto w = static_cast<uint32_t>(std::max(1.0, std::floor(source.width * scale)));
  const auto h = static_cast<uint32_t>(std::max(1.0, std::floor(source.height * scale)));
  for (uint32_t y = 0; y < std::min(h, height); ++y) {
    const uint32_t sy = std::min(source.height - 1, static_cast<uint32_t>(y / scale));
    for (uint32_t x = 0; x < std::min(w, width); ++x) {
      const uint32_t sx = std::min(source.width - 1, static_cast<uint32_t>(x / scale));
      std::copy_n(source.at(sx, sy), 4, out.at(x, y));
    }
  }
  return out;
}

std::vector<uint8_t> pack_rgba8(const image::ImageRGBA32F& display, bool bgr) {
  std::vector<uint8_t> bytes(display.pixels.size());
  for (size_t i = 0; i < display.pixels.size(); i += 4) {
    for (size_t c = 0; c < 4; ++c) {
      const float v = display.pixels[i + c];
      const float clamped = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
      const size_t dst = bgr && c < 3 ? 2 - c : c;
      bytes[i + dst] = static_cast<uint8_t>(std::lround(clamped * 255.0f));
    }
  }
  return bytes;
}

}  // namespace voxgi::viewer
