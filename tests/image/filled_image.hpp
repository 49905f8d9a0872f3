#pragma once
// A uniform test image, shared by the image metric tests.

#include <cstdint>

#include "engine/image/image.hpp"

namespace voxgi::image {

inline ImageRGBA32F filled(uint32_t w, uint32_t h, float r, float g, float b) {
  ImageRGBA32F image(w, h);
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      float* p = image.at(x, y);
      p[0] = r;
      p[1] = g;
      p[2] = b;
      p[3] = 1.0f;
    }
  }
  return image;
}

}  // namespace voxgi::image
