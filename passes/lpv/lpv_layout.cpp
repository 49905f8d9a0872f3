#include "passes/lpv/lpv_layout.hpp"

#include <bit>
#include <string>

namespace voxgi::passes::lpv {
namespace {

constexpr VkDeviceSize kVec4 = 16;
constexpr VkDeviceSize kInjectedHeaderBytes = 16;
constexpr VkDeviceSize kRecordVec4s = 5;
constexpr VkDeviceSize kWorkVec4s = 2 * 3;

const char* layout_text(LpvBuffer buffer) {
  switch (buffer) {
    case LpvBuffer::Injected:
      return "a 16-byte header and 12 integers per cell";
    case LpvBuffer::Levels:
      return "5 vec4 per cell of every octree level";
    case LpvBuffer::Work:
      return "6 vec4 per cell of every octree level";
    case LpvBuffer::Radiance:
      return "5 vec4 per cell";
  }
  return "";
}

bool per_octree_cell(LpvBuffer buffer) {
  return buffer == LpvBuffer::Levels || buffer == LpvBuffer::Work;
}

}  // namespace

VkDeviceSize lpv_buffer_bytes(LpvBuffer buffer, uint64_t cells) {
  switch (buffer) {
    case LpvBuffer::Injected:
      return kInjectedHeaderBytes + cells * kCoefficientsPerCell * sizeof(int32_t);
    case LpvBuffer::Levels:
    case LpvBuffer::Radiance:
      return cells * kRecordVec4s * kVec4;
    case LpvBuffer::Work:
      return cells * kWorkVec4s * kVec4;
  }
  return 0;
}

uint64_t lpv_cell_count(const graph::ResourceInfo& clipmap) {
  return lpv_octree_cell_count(clipmap, 1);
}

uint64_t lpv_octree_cell_count(const graph::ResourceInfo& clipmap, uint32_t octree_levels) {
  if (clipmap.kind != graph::ResourceKind::Clipmap || clipmap.clipmap_levels == 0) return 0;
  const uint64_t cascades = 2 * uint64_t(clipmap.clipmap_levels) - 1;
  uint64_t cells = 0;
  for (uint32_t o = 0; o < octree_levels; ++o) {
    const uint64_t r = clipmap.extent.width >> o;
    cells += r * r * r * cascades;
  }
  return cells;
}

uint64_t lpv_voxel_count(const graph::ResourceInfo& clipmap) {
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
    const uint32_t levels =
        per_octree_cell(buffer) ? static_cast<uint32_t>(query.number("octree_levels")) : 1;
    size.bytes = lpv_buffer_bytes(buffer, lpv_octree_cell_count(*clipmap, levels));
    return size;
  };
}

void check_lpv_buffer(graph::PassCheck& check, LpvBuffer buffer, const char* slot,
                      const char* clipmap_slot) {
  if (!check.has(slot) || !check.has(clipmap_slot)) return;
  const graph::ResourceInfo& bound = check.info(slot);
  const graph::ResourceInfo& clipmap = check.info(clipmap_slot);
  const uint32_t levels =
      per_octree_cell(buffer) ? static_cast<uint32_t>(check.integer("octree_levels")) : 1;
  const VkDeviceSize need = lpv_buffer_bytes(buffer, lpv_octree_cell_count(clipmap, levels));
  if (bound.buffer_size >= need) return;
  check.slot_error(slot, "buffer '" + bound.name + "' holds " + std::to_string(bound.buffer_size) +
                             " bytes, but " + layout_text(buffer) + " for the cells of '" +
                             clipmap.name + "' need " + std::to_string(need));
}

graph::ParamSpec octree_levels_param() {
  return {"octree_levels",
          graph::ParamType::Int,
          1.0,
          1.0,
          static_cast<double>(kMaxOctreeLevels),
          {},
          "levels of the octree LPV (seed 002 sec. 4.2): R, R/2, ... cells per side; 1 is the "
          "uniform LPV",
          false,
          true};
}

graph::ParamSpec merge_param() {
  return {"merge",
          graph::ParamType::Enum,
          0.0,
          0.0,
          0.0,
          {"shells", "index"},
          "how the octree levels combine (the same on lpv.propagate and lpv.merge): shells, "
          "each level counts the distances only it resolves and the levels add up; index, seed "
          "002's eq. 10, each cell takes the finest level that light reached, so nearer light "
          "hides farther light (docs/lpv.md)",
          false};
}

void check_octree_levels(graph::PassCheck& check, const char* clipmap_slot) {
  if (!check.has(clipmap_slot)) return;
  const graph::ResourceInfo& clipmap = check.info(clipmap_slot);
  const uint32_t levels = static_cast<uint32_t>(check.integer("octree_levels"));
  const uint32_t r = clipmap.extent.width;
  if (levels < 1 || r == 0) return;
  if (levels - 1 >= 32 || (r % (1u << (levels - 1))) != 0) {
    check.param_error("octree_levels", std::to_string(levels) + " octree levels halve the " +
                                           std::to_string(r) + " cells per side of '" +
                                           clipmap.name + "' " + std::to_string(levels - 1) +
                                           " times, which does not divide them; use " + "at most " +
                                           std::to_string(1 + std::countr_zero(r)) + " levels");
  }
}

}  // namespace voxgi::passes::lpv
