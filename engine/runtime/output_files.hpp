#pragma once
// Writing a graph's outputs the way `voxgi render` does (display → PNG, linear → EXR), and the
// images front ends derive from outputs: differences and slices of volumes.

#include <filesystem>
#include <string>
#include <vector>

#include "engine/graph/compiler.hpp"
#include "engine/image/image.hpp"

namespace voxgi::runtime {

class GraphInstance;

// Writes STEM.png from "display" and STEM.exr from "linear" (other image outputs as
// STEM-<name>.exr; extra outputs named "viewer.*" are skipped). Creates the folder. Returns
// the files written. Throws image::ImageError / std::runtime_error naming the path.
std::vector<std::filesystem::path> write_outputs(GraphInstance& graph,
                                                 const std::filesystem::path& stem);

// Writes `text` to `path` through a temporary file next to it and a rename, creating the
// folder. Throws std::runtime_error naming the path.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

// |a - b| per channel times `gain`, alpha 1. Throws std::invalid_argument when sizes differ.
image::ImageRGBA32F difference(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b,
                               float gain = 1.0f);
// Largest per-channel absolute difference over RGB, and the mean absolute difference.
struct DifferenceStats {
  float max_abs = 0.0f;
  double mean_abs = 0.0;
};
DifferenceStats difference_stats(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b);

// One 2D slice of a resource read back whole: a layer of an array image, a z slice of a 3D
// image, or z slice `slice` of clipmap level `level`. `texels` are RGBA floats as read_output
// returns them, in layer/slice-major order.
image::ImageRGBA32F slice_of(const graph::ResourceInfo& info, const std::vector<float>& texels,
                             uint32_t level, uint32_t slice);
// How many slices slice_of() accepts for `level` and how many levels there are.
uint32_t slice_count(const graph::ResourceInfo& info);
uint32_t level_count(const graph::ResourceInfo& info);

}  // namespace voxgi::runtime
