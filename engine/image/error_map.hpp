#pragma once
// Per-pixel error of an image against a reference, and a colour heat map of it for people to
// look at next to the two images.

#include <vector>

#include "engine/image/image.hpp"

namespace voxgi::image {

// Per-pixel relative squared error, the term compare_images() averages into relMSE: the mean
// over RGB of (a - b)^2 / (b^2 + 0.01). NaN where either pixel is not finite. Throws
// std::invalid_argument when the sizes differ or the images are empty.
std::vector<double> relative_error_per_pixel(const ImageRGBA32F& image,
                                             const ImageRGBA32F& reference);

struct HeatMapScale {
  // Errors at or below `low` are the coldest colour, at or above `high` the hottest; the ramp
  // between them is logarithmic because errors span orders of magnitude.
  double low = 1e-4;
  double high = 1.0;
};

// Display-referred RGBA (for write_png) of the per-pixel relative error on a black → purple →
// orange → yellow ramp; pixels where either image is not finite are magenta.
ImageRGBA32F relative_error_heat_map(const ImageRGBA32F& image, const ImageRGBA32F& reference,
                                     HeatMapScale scale = {});

// The colour of t in [0, 1] on the heat map's ramp (clamped), RGB in [0, 1].
void heat_map_colour(double t, float rgb[3]);

}  // namespace voxgi::image
