#pragma once
// Small helpers the family's passes share: slot declarations and dispatch sizes (compiling
// shaders and compute pipelines: engine/graph/pass_helpers.hpp).

#include <string>
#include <vector>

#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"

namespace voxgi::passes::common {

// Slot declarations the family's compute passes share.
// A 2D HDR radiance image (rgba16f or rgba32f) written as a storage image in compute.
graph::SlotSpec radiance_output(const char* name, const char* doc);

// Workgroup size of the family's 2D compute shaders (local_size_x = local_size_y).
inline constexpr uint32_t kTile = 8;

// Dispatches a kTile x kTile compute shader over a width x height image.
void dispatch_over_image(VkCommandBuffer cmd, uint32_t width, uint32_t height);

// Push-constant block for the family's full-screen compute passes.
struct ImageSize {
  uint32_t width;
  uint32_t height;
};

}  // namespace voxgi::passes::common
