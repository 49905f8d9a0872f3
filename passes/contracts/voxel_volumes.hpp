#pragma once
// Contract: the voxel volumes common.voxelize writes and every voxel family reads. GLSL twin:
// shaders/contracts/voxel_volumes.glsl, which documents what each channel holds and the
// surface-plane encoding of the normal volume's w.

#include <vulkan/vulkan.h>

#include "engine/graph/pass.hpp"

namespace voxgi::contracts {

inline constexpr VkFormat kVoxelAlbedoFormat = VK_FORMAT_R8G8B8A8_UNORM;
inline constexpr VkFormat kVoxelNormalFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kVoxelEmissionFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
inline constexpr VkFormat kVoxelFacesFormat = VK_FORMAT_R32G32B32A32_UINT;
// Per face group, its share of a voxel's light: written by an injection, read by vct.filter.
inline constexpr VkFormat kVoxelLightSharesFormat = VK_FORMAT_R32_UINT;

// An injection's optional "faces" slot: the voxelizer's faces, read with texelFetch in compute.
graph::SlotSpec voxel_faces_input();

// An injection's optional "light_shares" output (written with the radiance, from the faces),
// and the check that a pass writing it also reads the faces.
graph::SlotSpec voxel_light_shares_output();
void check_light_shares_have_faces(graph::PassCheck& check);

}  // namespace voxgi::contracts
