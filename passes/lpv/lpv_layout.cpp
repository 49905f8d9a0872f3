#include "passes/lpv/lpv_layout.hpp"

#include <string>

namespace voxgi::passes::lpv {
namespace {

constexpr VkDeviceSize kShCellBytes = kCoefficientsPerCell * sizeof(float);

VkDeviceSize sh_bytes(uint64_t cells, uint32_t copies) {
  return static_cast<VkDeviceSize>(cells) * kShCellBytes * copies;
}
VkDeviceSize injected_bytes(uint64_t cells) {
  return kInjectedHeaderBytes + static_cast<VkDeviceSize>(cells) * kCoefficientsPerCell * 4;
}

graph::SizeRule from_clipmap(const char* clipmap_slot, VkDeviceSize (*bytes)(uint64_t, uint32_t),
                             uint32_t copies) {
  return [clipmap_slot, bytes, copies](const graph::SizeQuery& query) {
    graph::DerivedSize size;
    const graph::ResourceInfo* clipmap = query.bound ? query.bound(clipmap_slot) : nullptr;
    if (!clipmap || lpv_cell_count(*clipmap) == 0) {
      size.unavailable = std::string("it has one cell per voxel of slot '") + clipmap_slot +
                         "', which is unbound, unsized or not a clipmap";
      return size;
    }
    size.bytes = bytes(lpv_cell_count(*clipmap), copies);
    return size;
  };
}

void check_buffer(graph::PassCheck& check, const char* slot, const char* clipmap_slot,
                  VkDeviceSize need, const char* what) {
  if (!check.has(slot)) return;
  const graph::ResourceInfo& buffer = check.info(slot);
  if (buffer.buffer_size >= need) return;
  check.slot_error(slot, "buffer '" + buffer.name + "' holds " +
                             std::to_string(buffer.buffer_size) + " bytes, but " + what +
                             " for the cells of '" + check.info(clipmap_slot).name + "' need " +
                             std::to_string(need));
}

}  // namespace

uint64_t lpv_cell_count(const graph::ResourceInfo& clipmap) {
  if (clipmap.kind != graph::ResourceKind::Clipmap) return 0;
  const uint64_t r = clipmap.extent.width;
  return r * r * r * clipmap.clipmap_levels;
}

graph::SizeRule injected_buffer_size(const char* clipmap_slot) {
  return from_clipmap(
      clipmap_slot, [](uint64_t cells, uint32_t) { return injected_bytes(cells); }, 1);
}

graph::SizeRule radiance_buffer_size(const char* clipmap_slot) {
  return from_clipmap(
      clipmap_slot, [](uint64_t cells, uint32_t) { return cells * kRadianceBytesPerCell; }, 1);
}

void check_radiance_buffer(graph::PassCheck& check, const char* slot, const char* clipmap_slot) {
  if (!check.has(clipmap_slot)) return;
  check_buffer(check, slot, clipmap_slot,
               lpv_cell_count(check.info(clipmap_slot)) * kRadianceBytesPerCell, "5 vec4 per cell");
}

graph::SizeRule sh_buffer_size(const char* clipmap_slot, uint32_t copies) {
  return from_clipmap(clipmap_slot, sh_bytes, copies);
}

void check_sh_buffer(graph::PassCheck& check, const char* slot, const char* clipmap_slot,
                     uint32_t copies) {
  if (!check.has(clipmap_slot)) return;
  check_buffer(check, slot, clipmap_slot,
               sh_bytes(lpv_cell_count(check.info(clipmap_slot)), copies),
               copies == 1 ? "12 floats per cell" : "12 floats per cell and copy");
}

void check_injected_buffer(graph::PassCheck& check, const char* slot, const char* clipmap_slot) {
  if (!check.has(clipmap_slot)) return;
  check_buffer(check, slot, clipmap_slot, injected_bytes(lpv_cell_count(check.info(clipmap_slot))),
               "a 16-byte header and 12 integers per cell");
}

}  // namespace voxgi::passes::lpv
