#pragma once
// RGBA float images and their PNG / EXR files. Writes are atomic: the data goes to a temporary
// file next to the target that is renamed over it only when complete, so a failed write never
// destroys an existing file.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace voxgi::image {

// The message names the path and the reason.
class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ImageRGBA32F {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> pixels;  // RGBA, row-major from the top row

  ImageRGBA32F() = default;
  ImageRGBA32F(uint32_t w, uint32_t h) : width(w), height(h), pixels(size_t(w) * h * 4, 0.0f) {}
  float* at(uint32_t x, uint32_t y) { return pixels.data() + (size_t(y) * width + x) * 4; }
  const float* at(uint32_t x, uint32_t y) const {
    return pixels.data() + (size_t(y) * width + x) * 4;
  }
};

// 8-bit RGBA PNG of display-referred values in [0,1] (already encoded, e.g. by the display
// transform); values are clamped and rounded to the nearest code, NaN writes 0.
void write_png(const std::filesystem::path& path, const ImageRGBA32F& display_referred);

enum class ExrPixelType { Half, Float };
// Linear RGBA EXR (OpenEXR 3, ZIP compression).
void write_exr(const std::filesystem::path& path, const ImageRGBA32F& linear,
               ExrPixelType type = ExrPixelType::Half);

// RGBA from an EXR. `layer` "" reads the bare R, G, B (A) channels, or the "Combined" layer of
// a multilayer file when there are none; otherwise the channels "<layer>.R" etc. (also
// "<anything>.<layer>.R", and parts named <layer> in multipart files). A single Y channel reads
// as grey; missing alpha reads as 1. Errors list the layers the file has.
ImageRGBA32F read_exr(const std::filesystem::path& path, std::string_view layer = "");
// The layer names read_exr accepts for this file ("" for bare channels).
std::vector<std::string> exr_layers(const std::filesystem::path& path);

// 8- or 16-bit PNG of any colour type, decoded to [0,1] RGBA without any colour conversion.
ImageRGBA32F read_png(const std::filesystem::path& path);

// True when any component is NaN or ±Inf; `count` (optional) gets the number of such pixels.
bool has_non_finite(const ImageRGBA32F& image, size_t* count = nullptr);

}  // namespace voxgi::image
