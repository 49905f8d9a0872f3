#pragma once
// Contract: the G-buffer common.gbuffer writes and screen-space passes of every family read.
// GLSL twin: shaders/contracts/gbuffer.glsl, which says what each channel holds and decodes
// it. Here: the targets' slot names and the formats they may have.

#include <vulkan/vulkan.h>

#include <array>
#include <vector>

#include "engine/graph/pass.hpp"

namespace voxgi::contracts {

// Colour targets in attachment order (gbuffer.frag's outputs 0..3).
inline constexpr std::array<const char*, 4> kGbufferColorSlots = {"base_color", "normal",
                                                                  "material", "emission"};

inline constexpr std::array<VkFormat, 2> kGbufferBaseColorFormats = {VK_FORMAT_R8G8B8A8_SRGB,
                                                                     VK_FORMAT_R16G16B16A16_SFLOAT};
inline constexpr std::array<VkFormat, 2> kGbufferNormalFormats = {VK_FORMAT_R16G16B16A16_SFLOAT,
                                                                  VK_FORMAT_R32G32B32A32_SFLOAT};
inline constexpr std::array<VkFormat, 2> kGbufferMaterialFormats = {VK_FORMAT_R8G8B8A8_UNORM,
                                                                    VK_FORMAT_R16G16B16A16_SFLOAT};
inline constexpr std::array<VkFormat, 2> kGbufferEmissionFormats = {VK_FORMAT_R16G16B16A16_SFLOAT,
                                                                    VK_FORMAT_R32G32B32A32_SFLOAT};
// Cleared to 1 (no surface).
inline constexpr VkFormat kGbufferDepthFormat = VK_FORMAT_D32_SFLOAT;

enum class GbufferTarget { BaseColor, Normal, Material, Emission, Depth };
std::vector<VkFormat> gbuffer_formats(GbufferTarget target);
// A reader's slot for one target, named as common.gbuffer names it: sampled in compute, in one
// of the target's formats.
graph::SlotSpec gbuffer_input(GbufferTarget target);

}  // namespace voxgi::contracts
