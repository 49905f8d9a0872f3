#include "passes/lpv/lpv_layout.hpp"

#include <string>

namespace voxgi::passes::lpv {
namespace {

constexpr VkDeviceSize kVec4 = 16;
constexpr VkDeviceSize kInjectedHeaderBytes = 16;

const char* layout_text(LpvBuffer buffer) {
  switch (buffer) {
    case LpvBuffer::Injected:
      return "a 16-byte header and 12 integers per cell";
    case LpvBuffer::Radiance:
      return "5 vec4 per cell";
    case LpvBuffer::Work:
      return "7 vec4 per cell";
  }
  return "";
}

}  // namespace

VkDeviceSize lpv_buffer_bytes(LpvBuffer buffer, uint64_t cells) {
  switch (buffer) {
    case LpvBuffer::Injected:
      return kInjectedHeaderBytes + cells * kCoefficientsPerCell * sizeof(int32_t);
    case LpvBuffer::Radiance:
      return cells * 5 * kVec4;
    case LpvBuffer::Work:
      return cells * (2 * 3 + 1) * kVec4;
  }
  return 0;
}

uint64_t lpv_cell_count(const graph::ResourceInfo& clipmap) {
  if (clipmap.kind != graph::ResourceKind::Clipmap) return 0;
  const uint64_t r = clipmap.extent.width;
  return r * r * r * clipmap.clipmap_levels;
}

graph::SizeRule lpv_buffer_size(LpvBuffer buffer, const char* clipmap_slot) {
  return [buffer, clipmap_slot](const graph::SizeQuery& query) {
    graph::DerivedSize size;
    const graph::ResourceInfo* clipmap = query.bound ? query.bound(clipmap_slot) : nullptr;
    if (!clipmap || lpv_cell_count(*clipmap) == 0) {
      size.unavailable = std::string("it has one cell per voxel of slot '") + clipmap_slot +
                         "', which is unbound, unsized or not a clipmap";
      return size;
    }
    size.bytes = lpv_buffer_bytes(buffer, lpv_cell_count(*clipmap));
    return size;
  };
}

void check_lpv_buffer(graph::PassCheck& check, LpvBuffer buffer, const char* slot,
                      const char* clipmap_slot) {
  if (!check.has(slot) || !check.has(clipmap_slot)) return;
  const graph::ResourceInfo& bound = check.info(slot);
  const graph::ResourceInfo& clipmap = check.info(clipmap_slot);
  const VkDeviceSize need = lpv_buffer_bytes(buffer, lpv_cell_count(clipmap));
  if (bound.buffer_size >= need) return;
  check.slot_error(slot, "buffer '" + bound.name + "' holds " + std::to_string(bound.buffer_size) +
                             " bytes, but " + layout_text(buffer) + " for the cells of '" +
                             clipmap.name + "' need " + std::to_string(need));
}

}  // namespace voxgi::passes::lpv
