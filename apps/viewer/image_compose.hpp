#pragma once
// What the viewer shows in its image area, made on the CPU from the graphs' read-back outputs:
// an A/B wipe, an inspected resource mapped to display values, and 8-bit packing for the
// swapchain. The images are small (the graph viewport), so this costs little next to rendering.

#include <cstdint>
#include <vector>

#include "engine/image/image.hpp"

namespace voxgi::viewer {

// Columns left of `split` (0..1 of the width) from `a`, the others from `b`. Sizes must match
// (throws std::invalid_argument).
image::ImageRGBA32F wipe(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b, float split);

enum class Channels { RGB, R, G, B, A };

// A resource's values as display values: × 2^exposure_ev, then the sRGB transfer function for
// linear data (display-referred data is shown as stored). NaN and Inf show magenta, negative
// values cyan, so problems stand out.
image::ImageRGBA32F inspect_to_display(const image::ImageRGBA32F& values, float exposure_ev,
                                       bool display_referred, Channels channels);

// Nearest-neighbour scaled to fit inside width × height (aspect kept, top-left aligned, the
// rest black), so a 64² volume slice or a 2048² shadow map fills the image area.
image::ImageRGBA32F fit_nearest(const image::ImageRGBA32F& source, uint32_t width, uint32_t height);

// RGBA8 (or BGRA8 with `bgr`) bytes of display values in [0,1], rows from the top.
std::vector<uint8_t> pack_rgba8(const image::ImageRGBA32F& display, bool bgr);

}  // namespace voxgi::viewer
