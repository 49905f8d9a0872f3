#pragma once
// Helpers the dvs passes share: slot declarations for voxel clipmaps and dispatch sizes over a
// volume (shaders, compute pipelines and input versions: engine/graph/pass_helpers.hpp).

#include <cstdint>
#include <string>
#include <vector>

#include "engine/graph/pass.hpp"
#include "engine/graph/pass_helpers.hpp"

namespace voxgi::passes::dvs {

// A clipmap read with texelFetch or a sampler in compute.
graph::SlotSpec clipmap_input(const char* name, const char* doc, bool optional = false,
                              std::vector<VkFormat> formats = {});
// An rgba16f clipmap written as a storage image in compute (its mip 0, or the bound mip).
graph::SlotSpec radiance_volume_output(const char* name, const char* doc, bool optional = false);

// The view a storage write of a volume slot goes to: the bound mip, or mip 0 when the slot is
// bound to the whole image (storage views hold one mip level).
VkImageView storage_view(const graph::BoundResource& resource);

// Workgroup edge of the family's 3D compute shaders (local size kVolumeTile^3).
inline constexpr uint32_t kVolumeTile = 4;
void dispatch_over_volume(VkCommandBuffer cmd, VkExtent3D extent);

}  // namespace voxgi::passes::dvs
