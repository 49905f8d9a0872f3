#pragma once
// What the viewer tests share: a small graph file they write themselves (so edits elsewhere
// to the shipped graphs do not change what they check), image comparison, and the viewer run
// under the test's Xvfb display.

#include <filesystem>
#include <string>
#include <vector>

#include "engine/image/image.hpp"
#include "tests/apps/child_process.hpp"

namespace voxgi::test {

// The foundation pipeline (G-buffer, shadows, direct light, constant ambient, composite,
// display) with the ambient pass's radiance set to `ambient`.
std::string test_graph_text(double ambient);
void write_file(const std::filesystem::path& file, const std::string& text);
// Writes through a temporary file and a rename, as editors do, so a poll never sees half.
void replace_file(const std::filesystem::path& file, const std::string& text);

// A glTF scene (embedded buffer): a grey floor, a white box-less quad that an animation slides
// along x over 1 s, a point light and a camera named "overview".
std::string animated_gltf_text();

struct ImageDifference {
  double max_abs = 0.0;
  double mean_abs = 0.0;
};
// Over RGB; throws when the sizes differ.
ImageDifference compare_images(const image::ImageRGBA32F& a, const image::ImageRGBA32F& b);
// Mean over RGB.
double mean_rgb(const image::ImageRGBA32F& picture);
// The number of distinct RGB values, to tell a real picture from a blank one.
size_t distinct_colors(const image::ImageRGBA32F& picture);

// Waits until `file` exists (or `seconds` pass).
bool wait_for_file(const std::filesystem::path& file, double seconds);

}  // namespace voxgi::test
