// Size rules shared by pass types (pass.hpp): what an output needs when the graph leaves its
// size to the pass that writes it.
#include <algorithm>
#include <stdexcept>
#include <string>

#include "engine/graph/pass.hpp"

namespace voxgi::graph {

double SizeQuery::number(std::string_view param) const {
  if (params) {
    auto it = params->find(std::string(param));
    if (it != params->end()) return it->second.number;
  }
  return 0.0;
}

std::string SizeQuery::choice(std::string_view param) const {
  if (params) {
    auto it = params->find(std::string(param));
    if (it != params->end()) return it->second.text;
  }
  return {};
}

void set_size_rule(PassTypeInfo& info, std::string_view slot, SizeRule rule) {
  for (SlotSpec& spec : info.outputs) {
    if (spec.name != slot) continue;
    spec.size_rule = std::move(rule);
    return;
  }
  throw std::logic_error("pass type '" + info.type + "' has no output slot '" + std::string(slot) +
                         "' to give a size rule");
}

double SizeQuery::scene_value(std::string_view feature) const {
  if (scene) {
    auto it = scene->find(std::string(feature));
    if (it != scene->end()) return it->second;
  }
  return 0.0;
}

SizeRule viewport_size(uint32_t divisor) {
  return [divisor](const SizeQuery& q) {
    DerivedSize size;
    size.width = std::max(1u, q.viewport_width / divisor);
    size.height = std::max(1u, q.viewport_height / divisor);
    size.depth = 1;
    return size;
  };
}

SizeRule same_layout_as(std::string slot, bool full_mips) {
  return [slot = std::move(slot), full_mips](const SizeQuery& q) {
    DerivedSize size;
    const ResourceInfo* other = q.bound ? q.bound(slot) : nullptr;
    if (!other) {
      size.unavailable = "it takes the layout of slot '" + slot + "', which is unbound or unsized";
      return size;
    }
    size.full_mips = full_mips;
    size.width = other->extent.width;
    size.height = other->extent.height;
    size.depth = other->extent.depth;
    size.layers = other->array_layers;
    size.resolution = other->kind == ResourceKind::Clipmap ? other->extent.width : 0;
    size.levels = other->clipmap_levels;
    size.bytes = other->buffer_size;
    return size;
  };
}

}  // namespace voxgi::graph
