#pragma once
// FLIP, the perceptual difference of an image flipped back and forth with its reference
// (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", HPG 2020), and its
// HDR form (Andersson et al., "Visualizing and Communicating Errors in Rendered Images",
// Ray Tracing Gems II, 2021): LDR-FLIP of tone-mapped copies of both images over a range of
// exposures chosen from the reference's luminance, the maximum per pixel.
//
// Per pixel 0 means indistinguishable and 1 the largest difference (pure green against pure
// blue). The viewing condition is a number of pixels per degree of visual angle; the default
// is the paper's: a 0.7 m wide 3840-pixel monitor seen from 0.7 m (about 67 pixels per degree).

#include <cstdint>
#include <vector>

#include "engine/image/image.hpp"

namespace voxgi::image {

struct FlipOptions {
  double pixels_per_degree = 0.7 * 3840.0 / 0.7 * 3.14159265358979323846 / 180.0;
};

struct FlipResult {
  std::vector<float> error;  // per pixel, row by row, in [0, 1]
  double mean = 0.0;
};

struct HdrFlipResult : FlipResult {
  // Exposures (in stops) from the reference's largest luminance (brightest pixel tone-maps
  // to 0.85) to its median luminance (median tone-maps to 0.85), and how many were evaluated.
  double start_exposure = 0.0;
  double stop_exposure = 0.0;
  uint32_t exposures = 0;
};

// LDR-FLIP of two images whose RGB are linear values in [0, 1] (what an sRGB display shows
// after decoding); values outside are clamped. Alpha is ignored. Throws std::invalid_argument
// when the sizes differ or an image is empty.
FlipResult ldr_flip(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                    const FlipOptions& options = {});

// HDR-FLIP of linear HDR radiance with the ACES filmic tone mapper. Negative and non-finite
// components count as 0. Throws std::invalid_argument as ldr_flip.
HdrFlipResult hdr_flip(const ImageRGBA32F& test, const ImageRGBA32F& reference,
                       const FlipOptions& options = {});

// The ACES fit the HDR-FLIP paper uses (Narkowicz's curve on 0.6 × the input), not clamped.
double flip_tone_map(double x);

}  // namespace voxgi::image
