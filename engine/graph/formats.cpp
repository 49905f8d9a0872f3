// Resource formats, kinds and the synchronisation state each slot access needs.
#include <array>

#include "engine/graph/compiler.hpp"

namespace voxgi::graph {

namespace {

struct FormatEntry {
  const char* name;
  VkFormat format;
  uint32_t bytes;
};

constexpr std::array kFormats = {
    FormatEntry{"r8", VK_FORMAT_R8_UNORM, 1},
    FormatEntry{"rg8", VK_FORMAT_R8G8_UNORM, 2},
    FormatEntry{"rgba8", VK_FORMAT_R8G8B8A8_UNORM, 4},
    FormatEntry{"rgba8_srgb", VK_FORMAT_R8G8B8A8_SRGB, 4},
    FormatEntry{"rgba16", VK_FORMAT_R16G16B16A16_UNORM, 8},
    FormatEntry{"r16f", VK_FORMAT_R16_SFLOAT, 2},
    FormatEntry{"rg16f", VK_FORMAT_R16G16_SFLOAT, 4},
    FormatEntry{"rgba16f", VK_FORMAT_R16G16B16A16_SFLOAT, 8},
    FormatEntry{"r32f", VK_FORMAT_R32_SFLOAT, 4},
    FormatEntry{"rg32f", VK_FORMAT_R32G32_SFLOAT, 8},
    FormatEntry{"rgba32f", VK_FORMAT_R32G32B32A32_SFLOAT, 16},
    FormatEntry{"r32ui", VK_FORMAT_R32_UINT, 4},
    FormatEntry{"r32i", VK_FORMAT_R32_SINT, 4},
    FormatEntry{"rg32ui", VK_FORMAT_R32G32_UINT, 8},
    FormatEntry{"rgba32ui", VK_FORMAT_R32G32B32A32_UINT, 16},
    FormatEntry{"r11g11b10f", VK_FORMAT_B10G11R11_UFLOAT_PACK32, 4},
    FormatEntry{"rgb10a2", VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4},
    FormatEntry{"d32f", VK_FORMAT_D32_SFLOAT, 4},
    FormatEntry{"d16", VK_FORMAT_D16_UNORM, 2},
};

VkPipelineStageFlags2 stage_mask(uint32_t stages) {
  VkPipelineStageFlags2 mask = 0;
  if (stages & kStageVertex) mask |= VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT;
  if (stages & kStageGeometry) mask |= VK_PIPELINE_STAGE_2_GEOMETRY_SHADER_BIT;
  if (stages & kStageFragment) mask |= VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
  if (stages & kStageCompute) mask |= VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
  if (stages & kStageTransfer) mask |= VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
  return mask;
}

}  // namespace

VkFormat format_from_name(std::string_view name) {
  for (const FormatEntry& f : kFormats) {
    if (name == f.name) return f.format;
  }
  return VK_FORMAT_UNDEFINED;
}

std::string format_name(VkFormat format) {
  for (const FormatEntry& f : kFormats) {
    if (format == f.format) return f.name;
  }
  return format == VK_FORMAT_UNDEFINED ? "none" : "vkformat" + std::to_string(format);
}

std::vector<std::string> format_names() {
  std::vector<std::string> names;
  for (const FormatEntry& f : kFormats) names.emplace_back(f.name);
  return names;
}

uint32_t format_texel_bytes(VkFormat format) {
  for (const FormatEntry& f : kFormats) {
    if (format == f.format) return f.bytes;
  }
  return 0;
}

bool is_depth_format(VkFormat format) {
  return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM;
}

std::string kind_name(ResourceKind kind) {
  switch (kind) {
    case ResourceKind::Image2D:
      return "image2d";
    case ResourceKind::Image3D:
      return "image3d";
    case ResourceKind::Clipmap:
      return "clipmap";
    case ResourceKind::Buffer:
      return "buffer";
  }
  return "?";
}

std::string access_name(Access access) {
  switch (access) {
    case Access::Sampled:
      return "sampled";
    case Access::StorageRead:
      return "storage-read";
    case Access::StorageWrite:
      return "storage-write";
    case Access::StorageReadWrite:
      return "storage-read-write";
    case Access::ColorAttachment:
      return "color-attachment";
    case Access::DepthAttachment:
      return "depth-attachment";
    case Access::UniformRead:
      return "uniform";
    case Access::TransferRead:
      return "transfer-read";
    case Access::TransferWrite:
      return "transfer-write";
    case Access::IndirectRead:
      return "indirect";
  }
  return "?";
}

bool access_writes(Access access) {
  switch (access) {
    case Access::StorageWrite:
    case Access::StorageReadWrite:
    case Access::ColorAttachment:
    case Access::DepthAttachment:
    case Access::TransferWrite:
      return true;
    default:
      return false;
  }
}

bool access_reads(Access access) {
  return !access_writes(access) || access == Access::StorageReadWrite;
}

ResourceState state_for(Access access, uint32_t stages, ResourceKind kind, VkFormat format) {
  const bool buffer = kind == ResourceKind::Buffer;
  const VkPipelineStageFlags2 shader = stage_mask(stages);
  ResourceState s;
  switch (access) {
    case Access::Sampled:
      // Depth images read in shaders (shadow maps) use the depth read-only layout.
      s.layout = is_depth_format(format) ? VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL
                                         : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
      s.stages = shader;
      s.access = buffer ? VK_ACCESS_2_SHADER_STORAGE_READ_BIT : VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
      break;
    case Access::StorageRead:
      s.layout = VK_IMAGE_LAYOUT_GENERAL;
      s.stages = shader;
      s.access = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
      break;
    case Access::StorageWrite:
      s.layout = VK_IMAGE_LAYOUT_GENERAL;
      s.stages = shader;
      s.access = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
      break;
    case Access::StorageReadWrite:
      s.layout = VK_IMAGE_LAYOUT_GENERAL;
      s.stages = shader;
      s.access = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
      break;
    case Access::ColorAttachment:
      s.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      s.stages = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
      s.access = VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
      break;
    case Access::DepthAttachment:
      s.layout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
      s.stages = VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                 VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
      s.access = VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
      break;
    case Access::UniformRead:
      s.stages = shader;
      s.access = VK_ACCESS_2_UNIFORM_READ_BIT;
      break;
    case Access::TransferRead:
      s.layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
      s.stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
      s.access = VK_ACCESS_2_TRANSFER_READ_BIT;
      break;
    case Access::TransferWrite:
      s.layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
      s.stages = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
      s.access = VK_ACCESS_2_TRANSFER_WRITE_BIT;
      break;
    case Access::IndirectRead:
      // Dispatch and draw commands read their arguments in the draw-indirect stage.
      s.stages = VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT;
      s.access = VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT;
      break;
  }
  if (buffer) s.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (s.stages == 0) s.stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;  // no stage declared
  return s;
}

}  // namespace voxgi::graph
